#include "p3at/verifier/verify.hpp"

namespace p3at::verifier {

const char* to_string(Region region) {
  switch (region) {
    case Region::unsuccessful: return "unsuccessful";
    case Region::uncertain: return "uncertain";
    case Region::successful: return "successful";
  }
  return "?";
}

}  // namespace p3at::verifier
