#include "p3at/sim/sim_drive_base.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace p3at::sim {
namespace {

// Quantise like the SIP counters a real bridge accumulates: position in the
// subclass's distance units, heading in 1/4096 turns. In-process runs then see
// the same odometry resolution as runs over ARCOS.
double quantise(double value, double step) { return std::round(value / step) * step; }

}  // namespace

SimDriveBase::SimDriveBase(World& world, std::size_t robot_index)
    : world_(world),
      robot_index_(robot_index),
      params_(arcos::RobotParams::for_subclass(world.robot(robot_index).config().subclass)),
      seen_cycle_(world.cycle_count()) {
  world_.robot(robot_index_).controller().enable_motors(true);
  refresh();
}

Status SimDriveBase::set_velocity(double trans_mps, double rot_radps) {
  if (state_.link != hal::LinkState::ok) {
    return make_error(Error::Code::state, "sim robot " + world_.robot(robot_index_).name() +
                                              ": motion refused (" + state_.why_stopped + ")");
  }
  if (!std::isfinite(trans_mps) || !std::isfinite(rot_radps)) {
    return make_error(Error::Code::invalid_argument, "set_velocity: velocities must be finite numbers");
  }
  MotionController& c = world_.robot(robot_index_).controller();
  if (trans_mps != 0.0 || rot_radps != 0.0) c.count_motion_command();
  c.command_trans_vel(trans_mps);
  c.command_rot_vel(rot_radps);
  return {};
}

Status SimDriveBase::stop() {
  world_.robot(robot_index_).controller().stop();
  return {};
}

Status SimDriveBase::emergency_stop() {
  world_.robot(robot_index_).controller().emergency_stop();
  refresh();
  return {};
}

void SimDriveBase::rearm() {
  world_.robot(robot_index_).controller().enable_motors(true);
  refresh();
}

Result<bool> SimDriveBase::wait_for_update(int timeout_ms) {
  if (world_.cycle_count() > seen_cycle_) {
    refresh();
    return true;
  }
  SimClock& clock = world_.clock();
  const std::int64_t next_update_us = world_.time_us() + kCycleUs;
  const std::int64_t deadline_us = clock.now_us() + static_cast<std::int64_t>(std::max(timeout_ms, 0)) * 1000;
  if (deadline_us < next_update_us) {
    clock.sleep_until_us(deadline_us);
    return false;
  }
  world_.step();
  refresh();
  return true;
}

void SimDriveBase::refresh() {
  const SimRobot& r = world_.robot(robot_index_);
  const MotionController& c = r.controller();
  const arcos::RobotParams& params = params_;
  seen_cycle_ = world_.cycle_count();
  hal::DriveState& s = state_;
  s.stamp_us = world_.clock().now_us();
  s.update_count = seen_cycle_;
  const Pose& odo = r.odometry();
  s.odometry.x_m = quantise(odo.x_m, params.dist_conv / 1000.0);
  s.odometry.y_m = quantise(odo.y_m, params.dist_conv / 1000.0);
  s.odometry.theta_rad = quantise(odo.theta_rad, params.angle_conv);
  s.left_vel_mps = r.left_wheel_mps();
  s.right_vel_mps = r.right_wheel_mps();
  s.trans_vel_mps = (s.left_vel_mps + s.right_vel_mps) / 2.0;
  s.rot_vel_radps = r.odometry_rot_vel_radps();
  const auto& ranges = r.sonar_ranges_m();
  for (std::size_t i = 0; i < s.sonar_m.size() && i < ranges.size(); ++i) s.sonar_m[i] = ranges[i];
  s.battery_v = 13.0;
  s.motors_enabled = c.motors_enabled();
  s.moving = r.moving();
  s.estop_pressed = c.estop();
  s.left_stall = r.left_stall();
  s.right_stall = r.right_stall();
  s.bumpers = 0;
  s.flags = static_cast<std::uint16_t>((c.motors_enabled() ? arcos::kFlagMotorsEnabled : 0u) |
                                       (c.estop() ? arcos::kFlagEstop : 0u));
  s.fault_flags = 0;
  if (c.estop()) {
    s.link = hal::LinkState::safety_stop;
    s.why_stopped = "emergency stop";
  } else {
    s.link = hal::LinkState::ok;
    s.why_stopped.clear();
  }
}

}  // namespace p3at::sim

