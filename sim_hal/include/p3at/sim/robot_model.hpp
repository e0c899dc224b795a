#pragma once
/// Every parameter of one simulated robot that is not fixed by the P3-AT's
/// design: its error model (the "real world" the verifier never reads) and its
/// motion limits. Defaults match MobileSim's P3-AT model where it has one.

#include <optional>
#include <string>

#include "p3at/sim/geometry.hpp"

namespace p3at::sim {

/// Dead-reckoning errors of the firmware's odometry.
struct OdometryErrors {
  /// Systematic: what the left / right encoder reports per metre the wheel really
  /// travels (1.0 = perfect; 1.01 = over-reports by 1 %, e.g. a worn, smaller tyre).
  double left_scale = 1.0;
  double right_scale = 1.0;
  /// Systematic skid-steer slip: the robot's effective track width divided by the
  /// track the firmware assumes (kNominalTrackM). Above 1 the robot really turns
  /// less than its odometry says.
  double track_ratio = 1.0;
  /// Random, drawn once per update (100 ms cycle): the update's odometric
  /// translation and rotation are each multiplied by (1 + N(0, sd²)) with sd these
  /// values ("error per unit travelled", MobileSim's default 0.0075).
  double random_trans_per_unit = 0.0075;
  double random_rot_per_unit = 0.0075;
};

/// Sonar ranging model.
struct SonarModel {
  double max_range_m = 5.0;   ///< a ray that meets nothing reads exactly this
  double noise_sd_m = 0.01;   ///< Gaussian noise added to a hit's range, then clamped to [0, max]
};

/// A yaw-rate gyro integrated by the firmware into its odometric heading (the
/// P3-AT's gyro correction): with one, the odometry turns by what the gyro
/// measures instead of by what the wheels say. Each 10 ms physics step it
/// measures (1 + scale_error) · true rate + bias + drift · t + N(0, noise²),
/// t the simulated time since power-up (docs/simulator.md, "Gyro").
struct GyroModel {
  double bias_degps = 0.0;          ///< constant rate bias at power-up, deg/s
  double drift_degps_per_s = 0.0;   ///< linear change of the bias with time, deg/s per s
  double noise_sd_degps = 0.0;      ///< white rate noise of each 10 ms sample, deg/s
  double scale_error = 0.0;         ///< measured / true rate - 1 (0.01: reads 1 % high)
};

/// The drive's physical limits and the firmware's default accelerations.
/// SETV/SETRV may lower the velocity maxima, never raise them above these tops.
struct MotionLimits {
  double max_trans_vel_mps = 0.6;          ///< MobileSim's P3-AT model
  double max_rot_vel_degps = 43.0;         ///< 0.75 rad/s, MobileSim's P3-AT model
  double trans_accel_mps2 = 0.3;           ///< ARCOS default, SETA changes it
  double trans_decel_mps2 = 0.6;
  double rot_accel_degps2 = 100.0;         ///< SETRA changes it
  double rot_decel_degps2 = 100.0;
};

/// Everything the world file says about one robot.
struct RobotConfig {
  std::string name = "robot1";
  Pose start;                       ///< true start pose, world frame
  std::string subclass = "p3at-sh"; ///< SYNC2 subclass: "p3at-sh" (DistConv 1.0) or "p3at" (0.465)
  int port = -1;                    ///< TCP port; -1 = the first port + robot index
  OdometryErrors odometry;
  SonarModel sonar;
  /// The gyro, if the robot has one (a `gyro:` block in the world file):
  /// absent, the odometric heading comes from the wheels alone.
  std::optional<GyroModel> gyro;
  MotionLimits limits;
};

}  // namespace p3at::sim
