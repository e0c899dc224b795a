#pragma once
/// Gyro-aided odometry: the odometry's and the gyro's heading changes weighted
/// by their expected errors, and the position re-integrated along the result.

#include <cstdint>
#include <optional>

#include "p3at/hal/drive_base.hpp"

namespace p3at::bridge {

/// 1-sigma error models. A skid-steered P3-AT's odometry heading is poor when
/// turning (wheels slip); a gyro's error grows with time instead.
struct HeadingFuserConfig {
  double odom_turn_error = 0.10;              ///< odometry heading error per radian turned
  double odom_drive_error_rad_per_m = 0.02;   ///< odometry heading error per metre driven
  double gyro_random_walk_rad_per_sqrt_s = 0.0005;  ///< angle random walk
  double gyro_residual_bias_radps = 0.001;    ///< bias left after estimation
  double gyro_scale_error = 0.01;             ///< gyro heading error per radian turned
};

/// Each update takes the change since the previous one:
///   Δθ = w·Δθ_gyro + (1 − w)·Δθ_odom,  w = σ²_odom / (σ²_odom + σ²_gyro)
/// with σ²_odom = (a·|Δθ_odom|)² + (b·|Δs|)² and σ²_gyro = q²·Δt + (r·Δt)² + (c·|Δθ_gyro|)².
/// Standing still, the odometry (which then reports no change) dominates; turning,
/// the gyro does. Without a gyro heading the odometry's change is used alone, and
/// the gyro re-enters without a jump. Position follows the odometry's signed
/// distance along the fused heading. Headings are continuous (not wrapped).
class HeadingFuser {
 public:
  explicit HeadingFuser(HeadingFuserConfig config = {}) : config_(config) {}

  /// `odometry`: the drive base's dead-reckoned pose; `gyro_heading_rad`: the
  /// integrated gyro heading, or nullopt when the gyro is not usable; `stamp_us`:
  /// the odometry's time. The first call adopts the odometry pose.
  hal::Pose2 update(const hal::Pose2& odometry, std::optional<double> gyro_heading_rad, std::int64_t stamp_us);

  /// The next update adopts its odometry pose again (e.g. after the odometry was reset).
  void reset() { initialized_ = false; }

  const hal::Pose2& pose() const { return pose_; }
  /// The gyro's weight w in the latest update (0 when it had none).
  double last_gyro_weight() const { return last_weight_; }

 private:
  HeadingFuserConfig config_;
  bool initialized_ = false;
  hal::Pose2 pose_{};
  hal::Pose2 last_odometry_{};
  std::optional<double> last_gyro_;
  std::int64_t last_stamp_us_ = 0;
  double last_weight_ = 0.0;
};

}  // namespace p3at::bridge
