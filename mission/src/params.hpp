#pragma once
// Reading the parameters of each behavior and trigger, with their defaults,
// types, ranges and the defaults a trigger takes from its source state.

#include <yaml-cpp/yaml.h>

#include <cstddef>

#include "p3at/mission/mission.hpp"
#include "yaml_reader.hpp"

namespace p3at::mission::detail {

/// Coordinates of start poses and goals, metres.
inline const Range kCoordinateRange{-10000.0, 10000.0};

/// Reads `params` of a state (the `state` mapping) running `kind`. `kind_mark`
/// locates a missing parameter when the state has no `params:`. For a Notify,
/// sets `message_mark` to where its message name is written.
BehaviorParams parse_behavior(const MapReader& state, BehaviorKind kind, const YAML::Mark& kind_mark,
                              YAML::Mark& message_mark);

/// Reads `params` of a transition firing on `kind`, out of `source` (the
/// transition's from-state) of `robot` (whose states are all read). Fills the
/// defaults taken from the source state. For Notified and MessageSent, sets
/// `message_mark` to where the message name is written (or the trigger, if defaulted).
TriggerParams parse_trigger(const MapReader& transition, TriggerKind kind, const YAML::Mark& kind_mark,
                            const RobotSpec& robot, const State& source, YAML::Mark& message_mark);

}  // namespace p3at::mission::detail
