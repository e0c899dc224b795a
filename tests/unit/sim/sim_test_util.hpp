#pragma once
// Shared helpers of the simulator tests: robots without random errors, and
// short ways to run a world.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "p3at/sim/world.hpp"

namespace p3at::sim::test {

inline constexpr double kDeg = std::numbers::pi / 180.0;

/// A robot with no random errors and noiseless sonar (systematic errors perfect too).
inline RobotConfig exact_robot(const std::string& name = "robot1", double x_m = 0.0, double y_m = 0.0,
                               double theta_deg = 0.0) {
  RobotConfig r;
  r.name = name;
  r.start = Pose{x_m, y_m, theta_deg * kDeg};
  r.odometry.random_trans_per_unit = 0.0;
  r.odometry.random_rot_per_unit = 0.0;
  r.sonar.noise_sd_m = 0.0;
  return r;
}

inline WorldConfig world_of(std::vector<RobotConfig> robots, std::vector<Segment> walls = {}) {
  WorldConfig w;
  w.robots = std::move(robots);
  w.walls = std::move(walls);
  return w;
}

/// Steps `world` for `seconds` of simulated time (whole cycles).
inline void run_for(World& world, double seconds) {
  const auto cycles = static_cast<int>(std::lround(seconds * 10.0));
  for (int i = 0; i < cycles; ++i) world.step();
}

}  // namespace p3at::sim::test
