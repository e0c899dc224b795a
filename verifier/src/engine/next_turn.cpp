#include "engine/next_turn.hpp"

#include <variant>
#include <vector>

namespace p3at::verifier::engine {

NextTurn next_turn(const mission::RobotSpec& robot, std::size_t state) {
  const mission::GoToGuardedParams* leg = nullptr;
  bool spin = false;
  std::vector<char> seen(robot.states.size(), 0);
  std::vector<std::size_t> todo;
  const auto follow = [&](std::size_t from, bool messages_too) {
    for (const std::size_t t : robot.states[from].outgoing) {
      const mission::Transition& tr = robot.transitions[t];
      // A still state left on a message (a Stop waiting for a teammate) keeps
      // the robot where it stood: its heading still decides the next turn.
      if (!messages_too && tr.kind() == mission::TriggerKind::notified) continue;
      if (tr.to < seen.size() && !seen[tr.to]) {
        seen[tr.to] = 1;
        todo.push_back(tr.to);
      }
    }
  };
  follow(state, false);
  while (!todo.empty()) {
    const std::size_t s = todo.back();
    todo.pop_back();
    const mission::BehaviorParams& b = robot.states[s].behavior;
    if (const auto* go = std::get_if<mission::GoToGuardedParams>(&b)) {
      if (leg != nullptr && !(go->goal == leg->goal)) return {};
      leg = go;
    } else if (std::holds_alternative<mission::SpinParams>(b)) {
      spin = true;
    } else {
      follow(s, true);
    }
  }
  if (spin) return {NextTurn::Kind::spin, nullptr};
  if (leg != nullptr) return {NextTurn::Kind::leg, leg};
  return {};
}

}  // namespace p3at::verifier::engine
