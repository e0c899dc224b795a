#pragma once
/// A hal::DriveBase wrapped by the CAN accessories: the safety node can stop it
/// within one control cycle, and its odometry heading is gyro-aided.

#include <cstdint>
#include <functional>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/drive_base.hpp"
#include "p3at/bridge/accessories/accessory_hub.hpp"

namespace p3at::bridge {

/// Re-enables the motors after a safety stop, e.g. `[&] { return arcos.enable_motors(true); }`.
using ReenableMotors = std::function<Status()>;

struct GuardConfig {
  int poll_slice_ms = 10;          ///< the accessory bus is polled at least this often inside wait_for_update
  bool gyro_aided_pose = true;     ///< state().odometry is the gyro-aided pose (else the inner odometry)
  bool log = true;                 ///< one line on stderr per trip and re-arm
  std::string log_name = "safety";
};

/// Decorator: forwards to `inner`, polling `hub` while it waits. On a trip it
/// calls inner.emergency_stop() at once (ESTOP, motors disabled), refuses
/// set_velocity() until rearm() succeeds, and reports link == safety_stop with
/// the reason in why_stopped (unless the inner link itself is not ok, whose
/// reason then wins). Holds references: inner, hub and clock must outlive it.
class GuardedDriveBase final : public hal::DriveBase {
 public:
  GuardedDriveBase(hal::DriveBase& inner, AccessoryHub& hub, hal::Clock& clock, ReenableMotors reenable,
                   GuardConfig config = {});

  /// Refused (Error::Code::state, naming the reason) while the safety latch is tripped.
  Status set_velocity(double trans_mps, double rot_radps) override;
  Status stop() override { return inner_.stop(); }
  Status emergency_stop() override { return inner_.emergency_stop(); }
  /// Waits for the inner update in slices of poll_slice_ms, polling the accessories between them.
  Result<bool> wait_for_update(int timeout_ms) override;
  const hal::DriveState& state() const override { return state_; }

  /// Polls the accessories once now (also done inside wait_for_update).
  const SafetyVerdict& check();

  /// Arms the safety latch and re-enables the motors. Fails (Error::Code::state)
  /// while the safety node is not clear.
  Status rearm();

  const SafetyVerdict& verdict() const { return verdict_; }
  std::uint64_t emergency_stops() const { return emergency_stops_; }
  /// Steady µs of the latest trip's emergency stop (0 if none yet).
  std::int64_t last_stop_us() const { return last_stop_us_; }

 private:
  void refresh_state();

  hal::DriveBase& inner_;
  AccessoryHub& hub_;
  hal::Clock& clock_;
  ReenableMotors reenable_;
  GuardConfig config_;
  SafetyVerdict verdict_;
  hal::DriveState state_;
  hal::Pose2 aided_{};
  std::uint64_t seen_update_ = 0;
  bool have_update_ = false;
  std::uint64_t emergency_stops_ = 0;
  std::int64_t last_stop_us_ = 0;
};

}  // namespace p3at::bridge
