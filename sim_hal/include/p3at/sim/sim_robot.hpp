#pragma once
/// One simulated Pioneer 3-AT: skid-steer unicycle kinematics driven by its
/// firmware's MotionController, the true pose, the firmware's dead-reckoned
/// odometry with systematic and random errors, stall detection, and the
/// 16-sonar ring. Owned by a World, which steps it.

#include <array>
#include <cstdint>
#include <span>
#include <vector>
#include <string>

#include "p3at/sim/geometry.hpp"
#include "p3at/sim/motion_controller.hpp"
#include "p3at/sim/p3at_model.hpp"
#include "p3at/sim/rng.hpp"
#include "p3at/sim/robot_model.hpp"

namespace p3at::sim {

class SimRobot {
 public:
  /// The robot's random numbers come from (world_seed, stream): the same pair
  /// gives the same run.
  SimRobot(RobotConfig config, std::uint64_t world_seed, std::uint64_t stream);

  const RobotConfig& config() const { return config_; }
  const std::string& name() const { return config_.name; }
  MotionController& controller() { return controller_; }
  const MotionController& controller() const { return controller_; }

  // --- ground truth (world frame)
  const Pose& true_pose() const { return true_pose_; }
  double true_trans_vel_mps() const { return true_trans_vel_mps_; }
  double true_rot_vel_radps() const { return true_rot_vel_radps_; }
  Footprint footprint() const { return {true_pose_, kP3atLengthM, kP3atWidthM}; }

  // --- what the firmware measures
  /// Dead-reckoned pose in the firmware's odometry frame: (0, 0, 0) at power-up and after SETO.
  const Pose& odometry() const { return odometry_; }
  /// The odometry expressed in the world frame: the start pose composed with odometry().
  Pose odometry_in_world() const;
  /// Signed odometric distance travelled since power-up (never reset), metres.
  double odometry_distance_m() const { return odometry_distance_m_; }
  /// Wheel velocities as the encoders measure them, m/s.
  double left_wheel_mps() const { return left_wheel_mps_; }
  double right_wheel_mps() const { return right_wheel_mps_; }
  /// The firmware's translational / rotational velocity estimate (encoders, nominal track).
  double odometry_trans_vel_mps() const { return controller_.trans_vel_mps(); }
  double odometry_rot_vel_radps() const { return controller_.rot_vel_radps(); }
  bool left_stall() const { return stalled_; }
  bool right_stall() const { return stalled_; }
  /// True while the wheels turn (SIP type 0x33).
  bool moving() const;
  /// Latest range per sonar (sonar-number order), metres; max range when nothing echoed.
  const std::array<double, kP3atSonarCount>& sonar_ranges_m() const { return sonar_m_; }

  /// SETO: odometry back to (0, 0, 0); a heading goal keeps its physical direction.
  void reset_odometry();

  // --- stepping (called by World)
  /// Starts a 100 ms update: draws this update's random odometry errors.
  void begin_cycle();
  /// One physics step of `dt_s` ending at `now_us`. `walls` and `others` (the
  /// other robots' footprints) block motion: a step that would touch them is not
  /// taken and the stall flags are set.
  void step(std::int64_t now_us, double dt_s, std::span<const Segment> walls, std::span<const Footprint> others);
  /// Ray-casts every sonar against `obstacles` (walls and other robots' edges).
  void update_sonar(std::span<const Segment> obstacles);
  std::vector<Segment> nearby_;  // obstacles within sonar reach, reused every cycle

 private:
  RobotConfig config_;
  Rng rng_;
  MotionController controller_;
  Pose true_pose_;
  double true_trans_vel_mps_ = 0.0;
  double true_rot_vel_radps_ = 0.0;
  Pose odometry_;
  double odometry_distance_m_ = 0.0;
  double left_wheel_mps_ = 0.0;
  double right_wheel_mps_ = 0.0;
  bool stalled_ = false;
  double trans_error_factor_ = 1.0;  ///< this update's (1 + N(0, sd²)) for translation
  double rot_error_factor_ = 1.0;
  std::array<double, kP3atSonarCount> sonar_m_{};
};

}  // namespace p3at::sim
