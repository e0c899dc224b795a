#pragma once
// The one YAML document of a file, read safely with yaml-cpp 0.7, shared by
// every YAML reader of the project (the mission loader here, the verifier's
// robot-models reader): each turns a Problem into its own located error.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace p3at::yaml_document {

/// What is wrong with the text, and where (yaml-cpp's 0-based mark).
struct Problem {
  YAML::Mark mark;
  std::string detail;
};

/// The root node of the single non-null document in `text`. Throws Problem
/// for malformed YAML ("malformed YAML: ..."), a second non-null document,
/// or none at all (`empty_detail`). Never loops: yaml-cpp 0.7 can report an
/// endless run of null documents on a stray ',' outside any flow collection,
/// which is caught and reported as the unexpected token it is.
YAML::Node load_single(std::string_view text, const std::string& empty_detail);

/// `text` for an error message: bytes outside printable ASCII as \xNN, cut
/// after `max_chars` with "...".
std::string show(std::string_view text, std::size_t max_chars = 48);

}  // namespace p3at::yaml_document
