#include "p3at/mission/names.hpp"

namespace p3at::mission {

bool is_valid_name(std::string_view text) {
  if (text.empty() || text.size() > 64) return false;
  if (text.front() >= '0' && text.front() <= '9') return false;
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

}  // namespace p3at::mission
