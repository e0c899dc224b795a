#pragma once
// Test double of hal::DriveBase shared by the CAN tests: a drive base with a
// fixed control cycle, velocity commands integrated into a true heading and an
// odometry heading with a scale error, and a record of emergency stops. Works
// on any hal::Clock: with sim::SimClock it runs in fast time, calling on_tick
// after every simulated millisecond (so in-process accessories can be stepped);
// with hal::SteadyClock it really waits.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/drive_base.hpp"

namespace p3at::test {

class TickingDriveBase final : public hal::DriveBase {
 public:
  explicit TickingDriveBase(hal::Clock& clock, std::int64_t cycle_us = 100'000)
      : clock_(clock), cycle_us_(cycle_us), next_cycle_us_(clock.now_us() + cycle_us), integrated_us_(clock.now_us()) {
    state_.link = hal::LinkState::ok;
    state_.motors_enabled = true;
  }

  /// Called after each simulated millisecond (and each real one) inside wait_for_update.
  std::function<void(std::int64_t now_us)> on_tick;
  /// Odometry heading change = (1 + odom_turn_scale_error) × true heading change.
  double odom_turn_scale_error = 0.0;

  Status set_velocity(double trans_mps, double rot_radps) override {
    ++set_velocity_calls;
    if (estop_latched_) return make_error(Error::Code::state, "ticking drive base: e-stop latched");
    catch_up();
    trans_mps_ = trans_mps;
    rot_radps_ = rot_radps;
    return {};
  }
  Status stop() override {
    catch_up();
    trans_mps_ = 0.0;
    rot_radps_ = 0.0;
    return {};
  }
  Status emergency_stop() override {
    catch_up();
    estop_latched_ = true;
    trans_mps_ = 0.0;
    rot_radps_ = 0.0;
    state_.motors_enabled = false;
    estop_times_us.push_back(clock_.now_us());
    return {};
  }
  /// What ArcosClient::enable_motors(true) does: clears the latch once the
  /// motors are on; fails with `enable_failure` (the latch kept) when that is set.
  Status enable_motors() {
    ++enable_calls;
    if (!enable_failure.empty()) return make_error(Error::Code::protocol, enable_failure);
    estop_latched_ = false;
    state_.motors_enabled = true;
    return {};
  }

  Result<bool> wait_for_update(int timeout_ms) override {
    const std::int64_t deadline_us = clock_.now_us() + std::int64_t{std::max(timeout_ms, 0)} * 1000;
    for (;;) {
      catch_up();
      const std::int64_t now_us = clock_.now_us();
      if (now_us >= next_cycle_us_) {
        produce_update(now_us);
        return true;
      }
      if (now_us >= deadline_us) return false;
      clock_.sleep_until_us(std::min({now_us + 1000, deadline_us, next_cycle_us_}));
      if (on_tick) on_tick(clock_.now_us());
    }
  }

  const hal::DriveState& state() const override { return state_; }

  double true_heading_rad() const { return true_heading_rad_; }
  double rot_radps() const { return rot_radps_; }
  double trans_mps() const { return trans_mps_; }
  bool estop_latched() const { return estop_latched_; }

  std::vector<std::int64_t> estop_times_us;
  int set_velocity_calls = 0;
  int enable_calls = 0;
  std::string enable_failure;  ///< non-empty: enable_motors() fails with it (ENABLE lost, e-stop pressed)

 private:
  // Integrates the motion up to the clock's present (a real clock oversleeps).
  void catch_up() {
    const std::int64_t now_us = clock_.now_us();
    if (now_us <= integrated_us_) return;
    const double dt_s = static_cast<double>(now_us - integrated_us_) * 1e-6;
    integrated_us_ = now_us;
    true_heading_rad_ += rot_radps_ * dt_s;
    const double dtheta_odom = (1.0 + odom_turn_scale_error) * rot_radps_ * dt_s;
    const double mid = state_.odometry.theta_rad + 0.5 * dtheta_odom;
    state_.odometry.x_m += trans_mps_ * dt_s * std::cos(mid);
    state_.odometry.y_m += trans_mps_ * dt_s * std::sin(mid);
    state_.odometry.theta_rad += dtheta_odom;
  }
  void produce_update(std::int64_t now_us) {
    next_cycle_us_ += cycle_us_;
    ++state_.update_count;
    state_.stamp_us = now_us;
    state_.trans_vel_mps = trans_mps_;
    state_.rot_vel_radps = rot_radps_;
    state_.left_vel_mps = trans_mps_ - rot_radps_ * 0.25;
    state_.right_vel_mps = trans_mps_ + rot_radps_ * 0.25;
    state_.moving = trans_mps_ != 0.0 || rot_radps_ != 0.0;
  }

  hal::Clock& clock_;
  std::int64_t cycle_us_;
  std::int64_t next_cycle_us_;
  std::int64_t integrated_us_;
  hal::DriveState state_;
  double trans_mps_ = 0.0;
  double rot_radps_ = 0.0;
  double true_heading_rad_ = 0.0;
  bool estop_latched_ = false;
};

}  // namespace p3at::test
