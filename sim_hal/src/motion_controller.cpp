#include "p3at/sim/motion_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "p3at/sim/geometry.hpp"

namespace p3at::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
// A MOVE or HEAD goal closer than this counts as reached (and holds still there).
constexpr double kMoveToleranceM = 0.002;
constexpr double kHeadingToleranceRad = 0.2 * kDegToRad;

// Moves `current` toward `wanted` by at most accel*dt when the speed grows and
// decel*dt when it shrinks; a reversal first stops at zero.
double ramp(double current, double wanted, double accel, double decel, double dt) {
  const bool speeding_up = (current >= 0.0 && wanted > current) || (current <= 0.0 && wanted < current);
  const double rate = (speeding_up ? accel : decel) * dt;
  const double next = current + std::clamp(wanted - current, -rate, rate);
  if ((current > 0.0 && next < 0.0) || (current < 0.0 && next > 0.0)) return 0.0;
  return next;
}

// The speed at which a goal `remaining` away can still be reached by braking at `decel`.
double braking_profile(double remaining, double max_vel, double decel, double tolerance) {
  if (std::abs(remaining) < tolerance) return 0.0;
  const double v = std::min(max_vel, std::sqrt(2.0 * decel * std::abs(remaining)));
  return remaining > 0.0 ? v : -v;
}

}  // namespace

MotionController::MotionController(const MotionLimits& limits)
    : limits_(limits),
      max_trans_vel_mps_(limits.max_trans_vel_mps),
      max_rot_vel_radps_(limits.max_rot_vel_degps * kDegToRad),
      trans_accel_mps2_(limits.trans_accel_mps2),
      trans_decel_mps2_(limits.trans_decel_mps2),
      rot_accel_radps2_(limits.rot_accel_degps2 * kDegToRad),
      rot_decel_radps2_(limits.rot_decel_degps2 * kDegToRad) {}

void MotionController::enable_motors(bool on) {
  if (on) {
    estop_ = false;
    motors_enabled_ = true;
    return;
  }
  // Disabled motors hold nothing: the robot halts and forgets its goals, so
  // re-enabling never restarts an old motion by surprise.
  motors_enabled_ = false;
  stop();
  trans_vel_mps_ = 0.0;
  rot_vel_radps_ = 0.0;
}

void MotionController::command_trans_vel(double vel_mps) {
  trans_mode_ = TransMode::velocity;
  trans_target_mps_ = std::clamp(vel_mps, -max_trans_vel_mps_, max_trans_vel_mps_);
}

void MotionController::command_rot_vel(double vel_radps) {
  rot_mode_ = RotMode::velocity;
  rot_target_radps_ = std::clamp(vel_radps, -max_rot_vel_radps_, max_rot_vel_radps_);
}

void MotionController::command_heading(double heading_rad) {
  rot_mode_ = RotMode::heading;
  heading_target_rad_ = wrap_angle(heading_rad);
}

void MotionController::command_move(double distance_m, double current_distance_m) {
  trans_mode_ = TransMode::position;
  move_target_m_ = current_distance_m + distance_m;
}

void MotionController::stop() {
  trans_mode_ = TransMode::velocity;
  rot_mode_ = RotMode::velocity;
  trans_target_mps_ = 0.0;
  rot_target_radps_ = 0.0;
}

void MotionController::emergency_stop() {
  stop();
  trans_vel_mps_ = 0.0;
  rot_vel_radps_ = 0.0;
  motors_enabled_ = false;
  estop_ = true;
}

void MotionController::set_max_trans_vel(double vel_mps) {
  if (vel_mps > 0.0) max_trans_vel_mps_ = std::min(vel_mps, limits_.max_trans_vel_mps);
}

void MotionController::set_max_rot_vel(double vel_radps) {
  if (vel_radps > 0.0) max_rot_vel_radps_ = std::min(vel_radps, limits_.max_rot_vel_degps * kDegToRad);
}

void MotionController::set_trans_accel(double accel_mps2) {
  if (accel_mps2 > 0.0) trans_accel_mps2_ = accel_mps2;
  if (accel_mps2 < 0.0) trans_decel_mps2_ = -accel_mps2;
}

void MotionController::set_rot_accel(double accel_radps2) {
  if (accel_radps2 > 0.0) rot_accel_radps2_ = accel_radps2;
  if (accel_radps2 < 0.0) rot_decel_radps2_ = -accel_radps2;
}

void MotionController::on_heading_reset(double old_heading_rad) {
  heading_target_rad_ = wrap_angle(heading_target_rad_ - old_heading_rad);
}

void MotionController::set_watchdog(bool armed, std::int64_t now_us, std::int64_t timeout_us) {
  watchdog_armed_ = armed;
  watchdog_timeout_us_ = timeout_us;
  last_command_us_ = now_us;
  watchdog_halted_ = false;
}

void MotionController::note_command(std::int64_t now_us) {
  last_command_us_ = now_us;
  watchdog_halted_ = false;
}

void MotionController::on_stall() {
  trans_vel_mps_ = 0.0;
  rot_vel_radps_ = 0.0;
}

void MotionController::step(std::int64_t now_us, double dt_s, double odom_heading_rad, double odom_distance_m) {
  if (watchdog_armed_ && !watchdog_halted_ && now_us - last_command_us_ >= watchdog_timeout_us_) {
    watchdog_halted_ = true;
    ++stats_.watchdog_trips;
  }
  if (!motors_enabled_ || estop_) {
    trans_vel_mps_ = 0.0;
    rot_vel_radps_ = 0.0;
    return;
  }
  double want_trans = 0.0;
  double want_rot = 0.0;
  if (!watchdog_halted_) {
    switch (trans_mode_) {
      case TransMode::velocity:
        want_trans = std::clamp(trans_target_mps_, -max_trans_vel_mps_, max_trans_vel_mps_);
        break;
      case TransMode::position:
        want_trans = braking_profile(move_target_m_ - odom_distance_m, max_trans_vel_mps_, trans_decel_mps2_,
                                     kMoveToleranceM);
        break;
    }
    switch (rot_mode_) {
      case RotMode::velocity:
        want_rot = std::clamp(rot_target_radps_, -max_rot_vel_radps_, max_rot_vel_radps_);
        break;
      case RotMode::heading:
        want_rot = braking_profile(wrap_angle(heading_target_rad_ - odom_heading_rad), max_rot_vel_radps_,
                                   rot_decel_radps2_, kHeadingToleranceRad);
        break;
    }
  }
  trans_vel_mps_ = ramp(trans_vel_mps_, want_trans, trans_accel_mps2_, trans_decel_mps2_, dt_s);
  rot_vel_radps_ = ramp(rot_vel_radps_, want_rot, rot_accel_radps2_, rot_decel_radps2_, dt_s);
}

}  // namespace p3at::sim
