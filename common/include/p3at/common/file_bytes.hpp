#pragma once
/// A whole file's bytes, for the readers that hash or check what they read
/// (the launch gate's mission hash, campaign parts): one way to read a file,
/// with errors that name it.

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "p3at/common/result.hpp"

namespace p3at {

/// The file's exact bytes. Errors name the path: not_found, io ("path:
/// cannot open: why", "path: read error"), or invalid_argument for a path
/// that is a directory or not a regular file.
inline Result<std::string> read_file_bytes(const std::string& path) {
  // A directory opens as a stream that reads nothing ("empty models file");
  // a FIFO would block. Say what the path is instead.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    return make_error(Error::Code::invalid_argument,
                      path + ": is " + (std::filesystem::is_directory(status) ? "a directory" : "not a regular file") +
                          ", expected a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    return make_error(err == ENOENT ? Error::Code::not_found : Error::Code::io,
                      path + ": cannot open: " + std::strerror(err));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return make_error(Error::Code::io, path + ": read error");
  return ss.str();
}

}  // namespace p3at
