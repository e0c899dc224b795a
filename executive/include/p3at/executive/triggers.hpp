#pragma once
/// The mission's triggers as the executive evaluates them (docs/executive.md).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "p3at/executive/schemas.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/mission/mission.hpp"

namespace p3at::exec {

/// One robot's view of the mission's messages, indexed like Mission::messages:
/// which it has received (for the whole mission, never forgotten) and the
/// sequence number of the latest notification it sent of each.
class MessageBook {
 public:
  explicit MessageBook(std::size_t message_count) : received_(message_count, 0), sent_seq_(message_count) {}

  /// Records that message `index` was received. True when it is new (false when
  /// already received, or out of range).
  bool mark_received(std::size_t index);
  bool received(std::size_t index) const { return index < received_.size() && received_[index] != 0; }

  /// Records this robot's notification of message `index` under sequence number `seq`.
  void record_sent(std::size_t index, std::uint64_t seq);
  /// Sequence number of the latest notification of `index` this robot sent, if any.
  std::optional<std::uint64_t> last_sent(std::size_t index) const;

 private:
  std::vector<std::uint8_t> received_;
  std::vector<std::optional<std::uint64_t>> sent_seq_;
};

/// Everything a trigger may look at in one cycle.
struct TriggerInputs {
  Pose<double> pose;            ///< mission frame, from odometry (the robot's belief)
  double turned_rad = 0.0;      ///< Σ|Δheading| since the source state was entered
  const MessageBook* messages = nullptr;
  const hal::TeamLink* team_link = nullptr;
};

/// True when `trigger` holds:
///   AtGoal       distance(pose, goal) <= radius_m
///   HasTurned    turned_rad >= (angle_deg − offset_deg) in radians
///   Notified     the message has been received (at any time during the mission)
///   MessageSent  this robot sent the message and every recipient acknowledged it
/// `message_index` is the trigger's message in Mission::messages (Notified and
/// MessageSent); a trigger whose message is unknown never holds.
bool trigger_holds(const mission::TriggerParams& trigger, std::optional<std::size_t> message_index,
                   const TriggerInputs& inputs);

}  // namespace p3at::exec
