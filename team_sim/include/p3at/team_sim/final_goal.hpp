#pragma once
/// Where a robot's mission ends, for measuring how close it got.

#include <optional>
#include <string>

#include "p3at/protocols/mission/mission.hpp"

namespace p3at::team_sim {

/// A robot's final goal: the goal of the GoToGuarded state(s) closest before
/// its final states (walking transitions backwards from every final state).
/// nullopt, with `why` set, when there is none or they disagree.
std::optional<mission::Point2> final_goal(const mission::RobotSpec& robot, std::string* why = nullptr);

}  // namespace p3at::team_sim
