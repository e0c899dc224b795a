#pragma once
/// One simulated Pioneer 3-AT: skid-steer unicycle kinematics driven by its
/// firmware's MotionController, the true pose, the firmware's dead-reckoned
/// odometry with systematic and random errors (its heading from an optional
/// gyro instead of the wheels), stall detection, and the 16-sonar ring.
/// Owned by a World, which steps it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

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
  /// The footprint with its heading's cosine and sine, kept up to date as the robot moves.
  const Box& box() const { return box_; }

  // --- what the firmware measures
  /// Dead-reckoned pose in the firmware's odometry frame: (0, 0, 0) at power-up and after SETO.
  /// With a gyro (config().gyro), its heading is the integrated gyro rate.
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
  /// Starts a 100 ms update: draws this update's random odometry errors,
  /// recomputes the headings' cosines and sines exactly (the substeps advance
  /// them by small rotations), and picks the `walls` the robot could touch
  /// before the update ends (its substeps test only those).
  void begin_cycle(std::span<const Segment> walls);
  /// One physics step of `dt_s` ending at `now_us`. The walls picked by
  /// begin_cycle() and `others` (the other robots) block motion: a step that
  /// would touch them is not taken and the stall flags are set.
  void step(std::int64_t now_us, double dt_s, std::span<const Box> others);
  /// Ray-casts every sonar against `walls` and the `others` robots' edges.
  /// `walls` must be the same, unchanged, at every call (the World's walls).
  void update_sonar(std::span<const Segment> walls, std::span<const Box> others);

 private:
  /// The odometric rotation of one physics step with a gyro: its measured
  /// rate (true rate `true_rate_radps` with its errors at `now_us`) × dt.
  double gyro_rotation(std::int64_t now_us, double dt_s, double true_rate_radps);

  RobotConfig config_;
  Rng rng_;
  std::optional<Rng> gyro_rng_;  ///< the gyro's noise, a stream of its own: the other draws stay as without a gyro
  MotionController controller_;
  Pose true_pose_;
  Box box_;  ///< true_pose_'s footprint with its heading's cosine and sine
  double true_trans_vel_mps_ = 0.0;
  double true_rot_vel_radps_ = 0.0;
  Pose odometry_;
  double odometry_cos_ = 1.0;  ///< cosine and sine of odometry_.theta_rad
  double odometry_sin_ = 0.0;
  bool moved_ = false;  ///< the poses moved since begin_cycle() last made their cosines and sines exact
  double odometry_distance_m_ = 0.0;
  double left_wheel_mps_ = 0.0;
  double right_wheel_mps_ = 0.0;
  bool stalled_ = false;
  double trans_error_factor_ = 1.0;  ///< this update's (1 + N(0, sd²)) for translation
  double rot_error_factor_ = 1.0;
  // 1 / left_scale, 1 / right_scale, 1 / (nominal track × track_ratio): the
  // physics multiplies by them every substep.
  double inv_left_scale_ = 1.0;
  double inv_right_scale_ = 1.0;
  double inv_true_track_ = 1.0;
  double cycle_reach_m_ = 0.0;  ///< nothing farther from the centre can touch the robot within one update
  std::array<double, kP3atSonarCount> sonar_m_{};

  // The sonar rays where the robot stood at the last update, each with its
  // nearest wall: walls never move, so these hold while the robot stands still.
  struct SonarRay {
    Vec2 origin;
    Vec2 direction;
    double wall_range_m = 0.0;
    bool wall_hit = false;
  };
  std::array<SonarRay, kP3atSonarCount> sonar_rays_{};
  bool sonar_rays_valid_ = false;
  Pose sonar_pose_;                              ///< true_pose_ when sonar_rays_ were cast
  const Segment* sonar_walls_source_ = nullptr;  ///< the walls they were cast against
  std::size_t sonar_walls_count_ = 0;

  // Scratch lists, reused every update (no allocation once they have grown).
  std::vector<Segment> contact_walls_;  ///< walls within cycle_reach_m_ at the update's start
  std::vector<Segment> sonar_walls_;    ///< walls within sonar reach
  std::vector<Box> sonar_boxes_;        ///< other robots within sonar reach
  std::vector<Segment> sonar_edges_;    ///< their edges, four per box
};

}  // namespace p3at::sim
