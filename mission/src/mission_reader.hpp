#pragma once
// Reading a whole mission document and checking the team's messages.

#include <yaml-cpp/yaml.h>

#include "p3at/mission/mission.hpp"
#include "yaml_reader.hpp"

namespace p3at::mission::detail {

/// Reads and validates the mission in the document `root`; throws MissionError.
Mission read_mission(const Source& src, const YAML::Node& root);

}  // namespace p3at::mission::detail
