#include "p3at/mission/mission.hpp"

namespace p3at::mission {

std::string_view to_string(BehaviorKind kind) {
  switch (kind) {
    case BehaviorKind::go_to_guarded: return "GoToGuarded";
    case BehaviorKind::spin: return "Spin";
    case BehaviorKind::stop: return "Stop";
    case BehaviorKind::notify: return "Notify";
  }
  return "?";
}

std::optional<BehaviorKind> behavior_kind_from_string(std::string_view name) {
  for (BehaviorKind kind : {BehaviorKind::go_to_guarded, BehaviorKind::spin, BehaviorKind::stop,
                            BehaviorKind::notify}) {
    if (to_string(kind) == name) return kind;
  }
  return std::nullopt;
}

BehaviorKind kind_of(const BehaviorParams& params) {
  // The variant's alternatives are declared in BehaviorKind order.
  return static_cast<BehaviorKind>(params.index());
}

std::string_view to_string(TriggerKind kind) {
  switch (kind) {
    case TriggerKind::at_goal: return "AtGoal";
    case TriggerKind::has_turned: return "HasTurned";
    case TriggerKind::notified: return "Notified";
    case TriggerKind::message_sent: return "MessageSent";
  }
  return "?";
}

std::optional<TriggerKind> trigger_kind_from_string(std::string_view name) {
  for (TriggerKind kind : {TriggerKind::at_goal, TriggerKind::has_turned, TriggerKind::notified,
                           TriggerKind::message_sent}) {
    if (to_string(kind) == name) return kind;
  }
  return std::nullopt;
}

TriggerKind kind_of(const TriggerParams& params) {
  return static_cast<TriggerKind>(params.index());
}

std::string_view to_string(AbortAction action) {
  switch (action) {
    case AbortAction::continue_and_warn: return "continue_and_warn";
    case AbortAction::stop_and_notify: return "stop_and_notify";
  }
  return "?";
}

std::optional<AbortAction> abort_action_from_string(std::string_view name) {
  for (AbortAction action : {AbortAction::continue_and_warn, AbortAction::stop_and_notify}) {
    if (to_string(action) == name) return action;
  }
  return std::nullopt;
}

std::optional<std::size_t> RobotSpec::find_state(std::string_view state_name) const {
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (states[i].name == state_name) return i;
  }
  return std::nullopt;
}

std::optional<std::size_t> Mission::find_robot(std::string_view robot_name) const {
  for (std::size_t i = 0; i < robots.size(); ++i) {
    if (robots[i].name == robot_name) return i;
  }
  return std::nullopt;
}

std::optional<std::size_t> Mission::find_message(std::string_view message_name) const {
  for (std::size_t i = 0; i < messages.size(); ++i) {
    if (messages[i].name == message_name) return i;
  }
  return std::nullopt;
}

}  // namespace p3at::mission
