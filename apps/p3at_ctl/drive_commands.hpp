#pragma once
// The motions p3at_ctl can drive, closed-loop on the robot's own odometry.

#include <atomic>
#include <cstdio>

#include "p3at/bridge/arcos_client.hpp"

namespace p3at::ctl {

struct DriveOptions {
  double vel_mm_s = 0.0;      // translational velocity
  double rotvel_deg_s = 0.0;  // rotational velocity
  double secs = 0.0;          // how long (open-loop drive)
  double square_m = 0.0;      // side of a square (closed-loop drive)
  double print_every_s = 0.5;
};

/// Prints the odometry header line.
void print_odometry_header(std::FILE* out);
/// Prints one odometry line at time t_s.
void print_odometry(std::FILE* out, double t_s, const hal::DriveState& state);

/// Drives at a constant velocity for `secs`; returns 0, or 1 if the link failed.
int drive_constant(bridge::ArcosClient& robot, hal::Clock& clock, const DriveOptions& options,
                   const std::atomic<bool>& interrupted);

/// Drives a square of side `square_m` counter-clockwise; returns 0, or 1 if the link failed.
int drive_square(bridge::ArcosClient& robot, hal::Clock& clock, const DriveOptions& options,
                 const std::atomic<bool>& interrupted);

}  // namespace p3at::ctl
