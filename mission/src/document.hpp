#pragma once
// Loading the one YAML document of a mission file, with every yaml-cpp
// failure turned into a located MissionError.

#include <yaml-cpp/yaml.h>

#include <string_view>

#include "yaml_reader.hpp"

namespace p3at::mission::detail {

/// The root node of the single document in `text`. Throws MissionError for
/// malformed YAML, an empty stream, or a second non-empty document.
YAML::Node load_single_document(const Source& src, std::string_view text);

}  // namespace p3at::mission::detail
