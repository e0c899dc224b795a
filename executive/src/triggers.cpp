#include "p3at/executive/triggers.hpp"

#include <cmath>
#include <type_traits>
#include <variant>

namespace p3at::exec {

bool MessageBook::mark_received(std::size_t index) {
  if (index >= received_.size() || received_[index] != 0) return false;
  received_[index] = 1;
  return true;
}

void MessageBook::record_sent(std::size_t index, std::uint64_t seq) {
  if (index < sent_seq_.size()) sent_seq_[index] = seq;
}

std::optional<std::uint64_t> MessageBook::last_sent(std::size_t index) const {
  if (index >= sent_seq_.size()) return std::nullopt;
  return sent_seq_[index];
}

bool trigger_holds(const mission::TriggerParams& trigger, std::optional<std::size_t> message_index,
                   const TriggerInputs& inputs) {
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  return std::visit(
      [&](const auto& params) -> bool {
        using T = std::decay_t<decltype(params)>;
        if constexpr (std::is_same_v<T, mission::AtGoalParams>) {
          const double dx = params.goal.x_m - inputs.pose.x_m;
          const double dy = params.goal.y_m - inputs.pose.y_m;
          return std::hypot(dx, dy) <= params.radius_m;
        } else if constexpr (std::is_same_v<T, mission::HasTurnedParams>) {
          return inputs.turned_rad >= (params.angle_deg - params.offset_deg) * kDegToRad;
        } else if constexpr (std::is_same_v<T, mission::NotifiedParams>) {
          return message_index && inputs.messages != nullptr && inputs.messages->received(*message_index);
        } else {
          static_assert(std::is_same_v<T, mission::MessageSentParams>);
          if (!message_index || inputs.messages == nullptr || inputs.team_link == nullptr) return false;
          const std::optional<std::uint64_t> seq = inputs.messages->last_sent(*message_index);
          return seq && inputs.team_link->acknowledged(*seq);
        }
      },
      trigger);
}

}  // namespace p3at::exec
