#include "p3at/bridge/accessories/heading_fuser.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::bridge {
namespace {

// Keeps both variances positive so the weight is defined when nothing moved.
constexpr double kVarianceFloor = 1e-15;

double square(double v) { return v * v; }

}  // namespace

hal::Pose2 HeadingFuser::update(const hal::Pose2& odometry, std::optional<double> gyro_heading_rad,
                                std::int64_t stamp_us) {
  if (gyro_heading_rad && !std::isfinite(*gyro_heading_rad)) gyro_heading_rad.reset();
  if (!initialized_) {
    initialized_ = true;
    pose_ = odometry;
    last_odometry_ = odometry;
    last_gyro_ = gyro_heading_rad;
    last_stamp_us_ = stamp_us;
    last_weight_ = 0.0;
    return pose_;
  }
  const double d_odom = odometry.theta_rad - last_odometry_.theta_rad;
  const double dx = odometry.x_m - last_odometry_.x_m;
  const double dy = odometry.y_m - last_odometry_.y_m;
  // Signed distance along the odometry's own mid-step heading (negative when reversing).
  const double odom_mid = last_odometry_.theta_rad + 0.5 * d_odom;
  const double ds = dx * std::cos(odom_mid) + dy * std::sin(odom_mid);
  const double dt_s = std::max(0.0, static_cast<double>(stamp_us - last_stamp_us_) * 1e-6);

  double d_theta = d_odom;
  last_weight_ = 0.0;
  if (gyro_heading_rad && last_gyro_) {
    const double d_gyro = *gyro_heading_rad - *last_gyro_;
    const double var_odom = square(config_.odom_turn_error * d_odom) +
                            square(config_.odom_drive_error_rad_per_m * ds) + kVarianceFloor;
    const double var_gyro = square(config_.gyro_random_walk_rad_per_sqrt_s) * dt_s +
                            square(config_.gyro_residual_bias_radps * dt_s) +
                            square(config_.gyro_scale_error * d_gyro) + kVarianceFloor;
    last_weight_ = var_odom / (var_odom + var_gyro);
    d_theta = last_weight_ * d_gyro + (1.0 - last_weight_) * d_odom;
  }
  const double mid = pose_.theta_rad + 0.5 * d_theta;
  pose_.x_m += ds * std::cos(mid);
  pose_.y_m += ds * std::sin(mid);
  pose_.theta_rad += d_theta;

  last_odometry_ = odometry;
  last_gyro_ = gyro_heading_rad;
  last_stamp_us_ = stamp_us;
  return pose_;
}

}  // namespace p3at::bridge
