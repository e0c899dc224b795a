#pragma once
/// The drive base as the executive sees it: velocity commands in, odometry and
/// sonar out, one update per controller cycle (100 ms on a Pioneer).
/// Implemented by bridge::ArcosClient (a real or emulated Pioneer over ARCOS),
/// bridge::GuardedDriveBase (the same behind the CAN safety node)
/// and by sim::SimDriveBase (in-process, fast time).

#include <array>
#include <cstdint>
#include <string>

#include "p3at/common/result.hpp"

namespace p3at::hal {

inline constexpr int kSonarCount = 16;

/// Pose in the odometry frame: metres and radians, heading counter-clockwise from +X.
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
};

/// Link and safety condition of the base. Anything but `ok` refuses motion.
enum class LinkState {
  disconnected,  ///< no session
  connecting,    ///< handshake in progress
  ok,            ///< SIPs arriving, motion allowed
  link_lost,     ///< no SIP for the link-loss timeout: motion refused until reconnect
  safety_stop,   ///< an e-stop, bumper or safety-node fault: motion refused until re-armed
};

constexpr const char* to_string(LinkState s) {
  switch (s) {
    case LinkState::disconnected: return "disconnected";
    case LinkState::connecting: return "connecting";
    case LinkState::ok: return "ok";
    case LinkState::link_lost: return "link-lost";
    case LinkState::safety_stop: return "safety-stop";
  }
  return "?";
}

/// Everything one controller cycle reports.
struct DriveState {
  std::int64_t stamp_us = 0;       ///< clock time the update arrived
  std::uint64_t update_count = 0;  ///< increments once per SIP
  Pose2 odometry;                  ///< dead-reckoned pose (wrap-free, accumulated from differences)
  double left_vel_mps = 0.0;       ///< wheel velocities reported by the controller
  double right_vel_mps = 0.0;
  double trans_vel_mps = 0.0;      ///< (left + right) / 2
  double rot_vel_radps = 0.0;      ///< ROTVEL when reported, else from the wheel difference
  std::array<double, kSonarCount> sonar_m{};  ///< latest range per sonar; < 0 = no reading yet
  double battery_v = 0.0;
  bool motors_enabled = false;
  bool moving = false;             ///< SIP type 0x33
  bool estop_pressed = false;      ///< FLAGS bit 5
  bool left_stall = false;
  bool right_stall = false;
  std::uint16_t bumpers = 0;       ///< bits 0-6 rear, 8-14 front (as in the SIP stall word, stall bits removed)
  std::uint16_t flags = 0;         ///< raw SIP FLAGS
  std::uint16_t fault_flags = 0;   ///< raw SIP FAULTFLAGS, 0 when not reported
  LinkState link = LinkState::disconnected;
  std::string why_stopped;         ///< non-empty when link != ok: the reason, for logs
};

/// Motion interface used by the executive. Commands are refused (Error::Code::state)
/// unless link == ok. No call blocks longer than one cycle.
class DriveBase {
 public:
  DriveBase() = default;
  DriveBase(const DriveBase&) = delete;
  DriveBase& operator=(const DriveBase&) = delete;
  virtual ~DriveBase() = default;

  /// Translational (m/s, + forward) and rotational (rad/s, + counter-clockwise) velocity.
  virtual Status set_velocity(double trans_mps, double rot_radps) = 0;

  /// Decelerates to a stop. Always allowed.
  virtual Status stop() = 0;

  /// Emergency stop: immediate halt, motors disabled. Always allowed.
  virtual Status emergency_stop() = 0;

  /// Processes input until the next controller update arrives or `timeout_ms` passes.
  /// Returns true when a new update arrived. Sends keep-alives as needed.
  virtual Result<bool> wait_for_update(int timeout_ms) = 0;

  /// The latest state. Valid until the next call on this object.
  virtual const DriveState& state() const = 0;
};

}  // namespace p3at::hal
