#pragma once

#include <cstddef>

#include "p3at/mission/mission.hpp"

namespace p3at::verifier::engine {

/// What the robot does next with its heading once a state ends by itself,
/// for ordering the state's end points (StateAnalysis::end_points): the next
/// leg turns toward its goal left or right depending on a few degrees of
/// heading, so the points must keep the headings apart rather than average
/// them (docs/verifier.md, "Which way the next leg turns").
struct NextTurn {
  enum class Kind {
    unknown,  ///< nothing turns next, or the exits lead to legs with different goals
    leg,      ///< every self-timed exit leads (through still states) to a leg toward `leg->goal`
    spin,     ///< an exit leads (through still states) to a Spin: the heading is carried through it
  };
  Kind kind = Kind::unknown;
  /// The next leg's parameters (one of them when several legs share the
  /// goal), in the robot's spec; null unless `kind` is `leg`.
  const mission::GoToGuardedParams* leg = nullptr;
};

/// Follows the state's self-timed exits (AtGoal, HasTurned, MessageSent)
/// through states that hold the robot still (Stop, Notify) to the first
/// motion states they reach. A message's exit is left out: a robot taken out
/// by a message is placed by the interruption model, not by these points.
NextTurn next_turn(const mission::RobotSpec& robot, std::size_t state);

}  // namespace p3at::verifier::engine
