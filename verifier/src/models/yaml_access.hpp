#pragma once
// Typed, located reading of yaml-cpp nodes for the robot-models file: every
// read checks the type and range and, on failure, throws ModelsError at the
// node with what was expected. The mapping reader and the pieces shared with
// the mission loader are common/yaml's (yaml_map.hpp, yaml_reader.hpp).

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/common/yaml_map.hpp"
#include "p3at/common/yaml_reader.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::models_detail {

/// Where errors are reported: throws ModelsError, "file:line:column: detail"
/// (the reader makes it a ModelsSource).
using Source = yaml_reader::Source;
using ModelsSource = yaml_reader::SourceOf<ModelsError>;
/// The shared mapping reader (common/yaml): a models file names keys by
/// their path, "robots[0].motion.cycle_s" (MapReader::at_path, map_at).
using yaml_reader::MapReader;
using yaml_reader::describe;
using yaml_reader::position;
using yaml_reader::Range;
using yaml_reader::read_number;

/// The root of the one non-empty YAML document in `text`; `what` completes
/// "empty <what>" when there is none. Throws ModelsError for malformed YAML
/// (guarding yaml-cpp 0.7's endless loop on a stray ',') or a second document.
YAML::Node load_document(const Source& src, std::string_view text, std::string_view what);

/// User text made safe to echo in a one-line message: control and non-ASCII
/// bytes escaped, cut after `max_chars`.
std::string show(std::string_view text, std::size_t max_chars = 48);

}  // namespace p3at::verifier::models_detail
