#pragma once
/// The motion controller inside a simulated robot's firmware: what ARCOS does
/// with VEL, RVEL, HEAD, MOVE, STOP, ENABLE, ... Velocity, heading and
/// position modes with acceleration-limited ramps, motor enable, e-stop, and
/// the command watchdog. It produces the wheel motion the firmware asks for
/// (as its encoders will measure it); SimRobot turns that into true motion.
/// Front ends (FirmwareEmulator, SimDriveBase) call the command methods and
/// decide themselves which commands count as motion commands (count_motion_command).

#include <cstdint>

#include "p3at/sim/robot_model.hpp"

namespace p3at::sim {

/// Counters a test or log can read. Never reset.
struct ControllerStats {
  /// Commands that asked for motion, as counted by the front ends: VEL/RVEL/ROTATE/VEL2 with a non-zero value,
  /// HEAD to a heading other than the current one, DHEAD/MOVE by a non-zero amount,
  /// SimDriveBase::set_velocity with a non-zero velocity. Counted even while the
  /// motors are disabled: the robot "received" them.
  std::uint64_t motion_commands = 0;
  std::uint64_t watchdog_trips = 0;  ///< times the watchdog halted the robot
};

class MotionController {
 public:
  /// Starts with motors disabled (like ARCOS after power-up), velocity mode,
  /// targets zero, current limits = the tops in `limits`, watchdog off.
  explicit MotionController(const MotionLimits& limits);

  // --- commands (units as in the method names; headings in the firmware's odometry frame)
  void enable_motors(bool on);
  /// Velocity mode: translational target, clamped to ±current max.
  void command_trans_vel(double vel_mps);
  /// Velocity mode: rotational target (+ = counter-clockwise), clamped to ±current max.
  void command_rot_vel(double vel_radps);
  /// Heading mode: turn to the absolute odometric heading `heading_rad` (any value; wrapped).
  void command_heading(double heading_rad);
  /// Position mode: travel `distance_m` (signed) along the heading, measured by odometry.
  void command_move(double distance_m, double current_distance_m);
  /// Both targets to zero (velocity mode): decelerates at the current decelerations.
  void stop();
  /// Immediate halt, motors disabled, e-stop flag set; ENABLE 1 clears it.
  void emergency_stop();
  /// SETV / SETRV: new current maxima (clamped to the tops); <= 0 is ignored.
  void set_max_trans_vel(double vel_mps);
  void set_max_rot_vel(double vel_radps);
  /// SETA / SETRA semantics: > 0 sets the acceleration, < 0 the deceleration (magnitude), 0 ignored.
  void set_trans_accel(double accel_mps2);
  void set_rot_accel(double accel_radps2);
  /// The odometric heading was reset to 0 (SETO) from `old_heading_rad`: a heading
  /// goal keeps pointing the same way physically.
  void on_heading_reset(double old_heading_rad);

  // --- watchdog
  /// Arms (or disarms) the watchdog; arming counts as a command at `now_us`.
  void set_watchdog(bool armed, std::int64_t now_us, std::int64_t timeout_us = 2'000'000);
  /// Any command packet arrived: feeds the watchdog and resumes after a trip.
  void note_command(std::int64_t now_us);

  /// The robot hit something: the wheels stop (current velocities become zero,
  /// targets stay, so the robot pushes again next step).
  void on_stall();

  /// One control step of `dt_s` ending at `now_us`, with odometric feedback.
  /// Updates and returns nothing; read trans_vel_mps()/rot_vel_radps() after it.
  void step(std::int64_t now_us, double dt_s, double odom_heading_rad, double odom_distance_m);

  // --- state
  double trans_vel_mps() const { return trans_vel_mps_; }   ///< what the wheels are doing now
  double rot_vel_radps() const { return rot_vel_radps_; }
  bool motors_enabled() const { return motors_enabled_; }
  bool estop() const { return estop_; }
  bool watchdog_halted() const { return watchdog_halted_; }
  bool in_heading_mode() const { return rot_mode_ == RotMode::heading; }
  double heading_target_rad() const { return heading_target_rad_; }
  double max_trans_vel_mps() const { return max_trans_vel_mps_; }
  double max_rot_vel_radps() const { return max_rot_vel_radps_; }
  double trans_accel_mps2() const { return trans_accel_mps2_; }
  double trans_decel_mps2() const { return trans_decel_mps2_; }
  double rot_accel_radps2() const { return rot_accel_radps2_; }
  double rot_decel_radps2() const { return rot_decel_radps2_; }
  const MotionLimits& limits() const { return limits_; }
  const ControllerStats& stats() const { return stats_; }
  /// Counts a motion command (used by the command methods and by front ends
  /// for commands whose effect they judge themselves).
  void count_motion_command() { ++stats_.motion_commands; }

 private:
  enum class TransMode { velocity, position };
  enum class RotMode { velocity, heading };

  MotionLimits limits_;
  TransMode trans_mode_ = TransMode::velocity;
  RotMode rot_mode_ = RotMode::velocity;
  double trans_target_mps_ = 0.0;
  double rot_target_radps_ = 0.0;
  double heading_target_rad_ = 0.0;
  double move_target_m_ = 0.0;  ///< odometric distance at which a MOVE ends
  double trans_vel_mps_ = 0.0;
  double rot_vel_radps_ = 0.0;
  double max_trans_vel_mps_;
  double max_rot_vel_radps_;
  double trans_accel_mps2_;
  double trans_decel_mps2_;
  double rot_accel_radps2_;
  double rot_decel_radps2_;
  bool motors_enabled_ = false;
  bool estop_ = false;
  bool watchdog_armed_ = false;
  bool watchdog_halted_ = false;
  std::int64_t watchdog_timeout_us_ = 2'000'000;
  std::int64_t last_command_us_ = 0;
  ControllerStats stats_;
};

}  // namespace p3at::sim
