#include "models/text_file.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace p3at::verifier::models_detail {

bool read_text_file(const std::string& path, std::string& text, std::string& why) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    why = ec && ec != std::errc::no_such_file_or_directory ? ec.message() : "no such file";
    return false;
  }
  if (std::filesystem::is_directory(status)) {
    why = "it is a directory";
    return false;
  }
  if (!std::filesystem::is_regular_file(status)) {
    why = "not a regular file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    why = std::strerror(errno);
    return false;
  }
  // Read in chunks up to the limit rather than trusting the size the file
  // had a moment ago.
  text.clear();
  std::array<char, 65536> chunk{};
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) {
      why = "too large (limit " + std::to_string(kMaxFileBytes) + " bytes)";
      return false;
    }
  }
  if (in.bad()) {
    why = "read error";
    return false;
  }
  return true;
}

}  // namespace p3at::verifier::models_detail
