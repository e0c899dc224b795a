#pragma once
// An in-process hal::DriveBase for unit tests: a perfect unicycle that moves at
// exactly the commanded velocities, with odometry that reports the motion from
// a settable origin (to check that consumers re-zero it). Updates are produced
// by step(), or by wait_for_update() when a clock is attached (fast time: the
// clock jumps one 100 ms cycle per update). Every call is counted.

#include <cmath>
#include <cstdint>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/drive_base.hpp"

namespace p3at::test {

class FakeDriveBase final : public hal::DriveBase {
 public:
  static constexpr std::int64_t kCycleUs = 100'000;

  /// `clock` (optional, not owned) stamps updates; wait_for_update() advances it.
  explicit FakeDriveBase(hal::Clock* clock = nullptr) : clock_(clock) {
    state_.link = hal::LinkState::ok;
    state_.motors_enabled = true;
    state_.sonar_m.fill(-1.0);
    publish();
  }

  // ---- hal::DriveBase
  Status set_velocity(double trans_mps, double rot_radps) override {
    ++set_velocity_calls;
    if (refuse_motion) return make_error(Error::Code::state, "fake drive: motion refused by the test");
    if (state_.link != hal::LinkState::ok) {
      return make_error(Error::Code::state, std::string("fake drive: motion refused, link ") + hal::to_string(state_.link));
    }
    trans_cmd_mps = trans_mps;
    rot_cmd_radps = rot_radps;
    return {};
  }
  Status stop() override {
    ++stop_calls;
    trans_cmd_mps = 0.0;
    rot_cmd_radps = 0.0;
    return {};
  }
  Status emergency_stop() override {
    ++emergency_stop_calls;
    trans_cmd_mps = 0.0;
    rot_cmd_radps = 0.0;
    return {};
  }
  /// With updates on: advances the clock (if any) by one cycle, steps, returns true.
  /// With updates off: advances the clock by `timeout_ms` and returns false.
  Result<bool> wait_for_update(int timeout_ms) override {
    ++wait_calls;
    if (!deliver_updates) {
      if (clock_ != nullptr) clock_->sleep_until_us(clock_->now_us() + std::int64_t{timeout_ms} * 1000);
      return false;
    }
    if (clock_ != nullptr) clock_->sleep_until_us(clock_->now_us() + kCycleUs);
    step();
    return true;
  }
  const hal::DriveState& state() const override { return state_; }

  // ---- test controls
  /// Integrates the commanded velocities for `dt_s` (exact unicycle arc) and
  /// publishes one update (update_count + 1).
  void step(double dt_s = 0.1) {
    const double v = trans_cmd_mps;
    const double w = rot_cmd_radps;
    const double th = true_theta_rad;
    if (std::abs(w) < 1e-12) {
      true_x_m += v * dt_s * std::cos(th);
      true_y_m += v * dt_s * std::sin(th);
    } else {
      true_x_m += v / w * (std::sin(th + w * dt_s) - std::sin(th));
      true_y_m += -v / w * (std::cos(th + w * dt_s) - std::cos(th));
    }
    true_theta_rad += w * dt_s;
    ++state_.update_count;
    publish();
  }

  /// The odometry frame's origin: odometry = origin ⊕ (true motion since construction).
  void set_odometry_origin(const hal::Pose2& origin) {
    origin_ = origin;
    publish();
  }
  /// Changes the link state (and the reason given), as a bridge would.
  void set_link(hal::LinkState link, std::string why = {}) {
    state_.link = link;
    state_.why_stopped = std::move(why);
  }
  hal::DriveState& mutable_state() { return state_; }

  bool deliver_updates = true;
  bool refuse_motion = false;
  double trans_cmd_mps = 0.0;
  double rot_cmd_radps = 0.0;
  // Motion since construction, in the robot's starting frame (+x = initial heading).
  double true_x_m = 0.0;
  double true_y_m = 0.0;
  double true_theta_rad = 0.0;
  int set_velocity_calls = 0;
  int stop_calls = 0;
  int emergency_stop_calls = 0;
  int wait_calls = 0;

 private:
  void publish() {
    const double c = std::cos(origin_.theta_rad);
    const double s = std::sin(origin_.theta_rad);
    state_.odometry.x_m = origin_.x_m + c * true_x_m - s * true_y_m;
    state_.odometry.y_m = origin_.y_m + s * true_x_m + c * true_y_m;
    state_.odometry.theta_rad = origin_.theta_rad + true_theta_rad;
    state_.trans_vel_mps = trans_cmd_mps;
    state_.rot_vel_radps = rot_cmd_radps;
    state_.stamp_us = clock_ != nullptr ? clock_->now_us() : 0;
  }

  hal::Clock* clock_;
  hal::Pose2 origin_;
  hal::DriveState state_;
};

}  // namespace p3at::test
