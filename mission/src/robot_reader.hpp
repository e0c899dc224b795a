#pragma once
// Reading one robot (pose, URLs, states, transitions) and checking its FSA.

#include <yaml-cpp/yaml.h>

#include <vector>

#include "p3at/mission/mission.hpp"
#include "yaml_reader.hpp"

namespace p3at::mission::detail {

/// Where a robot's parts were written, for errors found after it is read.
struct RobotMarks {
  YAML::Mark name;
  std::vector<YAML::Mark> notify_message;   ///< per state; meaningful for Notify states
  std::vector<YAML::Mark> trigger_message;  ///< per transition; meaningful for Notified/MessageSent
};

/// Reads one item of `robots:`; checks everything local to the robot,
/// including that every state is reachable and some state is final.
RobotSpec read_robot(const Source& src, const YAML::Node& node, const YAML::Mark& fallback, RobotMarks& marks);

}  // namespace p3at::mission::detail
