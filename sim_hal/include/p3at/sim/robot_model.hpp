#pragma once
/// Every parameter of one simulated robot that is not fixed by the P3-AT's
/// design: its error model (the "real world" the verifier never reads) and its
/// motion limits. Defaults match MobileSim's P3-AT model where it has one.

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

/// Gyro error placeholders (no simulated gyro yet; loaded and validated now so
/// world files written today stay valid).
struct GyroModel {
  double bias_degps = 0.0;          ///< constant rate bias, deg/s
  double drift_degps_per_s = 0.0;   ///< linear change of the bias, deg/s per s
  double noise_sd_degps = 0.0;      ///< white rate noise, deg/s
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
  GyroModel gyro;
  MotionLimits limits;
};

}  // namespace p3at::sim
