#include "p3at/bridge/odometry_tracker.hpp"

#include <cmath>

namespace p3at::bridge {

const hal::Pose2& OdometryTracker::update(std::uint16_t xpos, std::uint16_t ypos, std::int16_t thpos) {
  if (!have_reference_) {
    reference_th_ = thpos;
    heading_units_ = 0;
    have_reference_ = true;
  }
  if (!have_previous_) {
    // After a reconnect the firmware heading may have restarted; keep our
    // accumulated heading and re-anchor the reference to it.
    reference_th_ = static_cast<std::int16_t>(thpos - heading_units_ % 4096);
    prev_x_ = xpos;
    prev_y_ = ypos;
    prev_th_ = thpos;
    have_previous_ = true;
    return pose_;
  }
  const double dx_mm = arcos::wrap_delta_15bit(prev_x_, xpos) * params_.dist_conv;
  const double dy_mm = arcos::wrap_delta_15bit(prev_y_, ypos) * params_.dist_conv;
  heading_units_ += arcos::wrap_delta_heading(prev_th_, thpos);
  prev_x_ = xpos;
  prev_y_ = ypos;
  prev_th_ = thpos;

  // The firmware's X/Y axes are its own; rotate its displacement into our
  // frame, whose +x is the firmware heading at the reference SIP.
  const double ref = static_cast<double>(reference_th_) * params_.angle_conv;
  const double c = std::cos(ref);
  const double s = std::sin(ref);
  pose_.x_m += (c * dx_mm + s * dy_mm) / 1000.0;
  pose_.y_m += (-s * dx_mm + c * dy_mm) / 1000.0;
  pose_.theta_rad = static_cast<double>(heading_units_) * params_.angle_conv;
  return pose_;
}

}  // namespace p3at::bridge
