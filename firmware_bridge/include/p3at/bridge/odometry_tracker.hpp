#pragma once
/// Turns the SIP's wrapping raw position counters into a continuous pose.

#include <cstdint>

#include "p3at/hal/drive_base.hpp"
#include "p3at/protocols/arcos/sip.hpp"

namespace p3at::bridge {

/// Accumulates pose from differences between consecutive SIPs, so the 15-bit
/// X/Y counters and the 4096-per-turn heading may wrap any number of times.
/// The pose starts at (0, 0, 0) on the first SIP after construction or
/// rebaseline(): x along the robot's heading at that moment. Heading is
/// continuous (not wrapped to ±π), which is what HasTurned-style triggers need.
class OdometryTracker {
 public:
  explicit OdometryTracker(const arcos::RobotParams& params) : params_(params) {}

  /// Feeds one SIP's raw position; returns the updated pose.
  const hal::Pose2& update(std::uint16_t xpos, std::uint16_t ypos, std::int16_t thpos);

  /// The next SIP becomes a new baseline; the pose continues from where it is
  /// (used after a reconnect, when the controller's counters may have restarted).
  void rebaseline() { have_previous_ = false; }

  /// Sets the pose to zero and rebaselines on the next SIP.
  void reset() {
    pose_ = {};
    heading_units_ = 0;
    have_reference_ = false;
    have_previous_ = false;
  }

  const hal::Pose2& pose() const { return pose_; }

 private:
  arcos::RobotParams params_;
  hal::Pose2 pose_{};
  bool have_previous_ = false;
  bool have_reference_ = false;
  std::uint16_t prev_x_ = 0;
  std::uint16_t prev_y_ = 0;
  std::int16_t prev_th_ = 0;
  std::int16_t reference_th_ = 0;  // firmware heading that maps to pose heading 0
  std::int64_t heading_units_ = 0;  // accumulated heading since the reference, in 4096/turn units
};

}  // namespace p3at::bridge
