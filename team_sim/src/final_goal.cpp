#include "p3at/team_sim/final_goal.hpp"

#include <deque>
#include <variant>
#include <vector>

namespace p3at::team_sim {

std::optional<mission::Point2> final_goal(const mission::RobotSpec& robot, std::string* why) {
  // Breadth-first backwards from the final states; the first GoToGuarded states
  // met on each path are the last moves of the mission.
  const std::size_t n = robot.states.size();
  std::vector<bool> seen(n, false);
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < n; ++i) {
    if (robot.is_final(i)) {
      seen[i] = true;
      queue.push_back(i);
    }
  }
  std::optional<mission::Point2> goal;
  while (!queue.empty()) {
    const std::size_t s = queue.front();
    queue.pop_front();
    if (const auto* go = std::get_if<mission::GoToGuardedParams>(&robot.states[s].behavior)) {
      if (goal && !(*goal == go->goal)) {
        if (why) *why = "robot '" + robot.name + "' ends at more than one GoToGuarded goal";
        return std::nullopt;
      }
      goal = go->goal;
      continue;  // do not look past the last move on this path
    }
    for (const auto& t : robot.transitions) {
      if (t.to == s && !seen[t.from]) {
        seen[t.from] = true;
        queue.push_back(t.from);
      }
    }
  }
  if (!goal && why) *why = "robot '" + robot.name + "' has no GoToGuarded state before its final state";
  return goal;
}

}  // namespace p3at::team_sim
