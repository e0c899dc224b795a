#pragma once
// Reading a whole configuration file, refusing what is not one: directories,
// devices and FIFOs (which could block or never end) and anything huge.

#include <cstddef>
#include <string>

namespace p3at::verifier::models_detail {

/// Larger than any sensible models or world file; keeps a wrong path (a log,
/// a disk image) from being slurped.
constexpr std::size_t kMaxFileBytes = 16 * 1024 * 1024;

/// Reads the regular file at `path` into `text`. On failure returns false
/// with the reason in `why` ("no such file", "it is a directory", ...).
bool read_text_file(const std::string& path, std::string& text, std::string& why);

}  // namespace p3at::verifier::models_detail
