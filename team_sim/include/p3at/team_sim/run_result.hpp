#pragma once
/// What one fast-time run of a team gives (team_run.hpp makes them); plain
/// data, so the figures over runs and a shard's part (p3at_team_stats) need
/// neither the executive nor the simulator.

#include <cstdint>
#include <string>
#include <vector>

namespace p3at::team_sim {

struct RobotResult {
  std::string name;
  std::string phase;                 ///< "finished", "aborted", "running" (timed out)
  std::string reason;                ///< why aborted
  double end_time_s = 0.0;           ///< when its FSA ended (or the run's end)
  /// True final position (world frame): for a successful run where the robot
  /// came to rest after entering its final state, else where it stood when the run ended.
  double true_x_m = 0.0, true_y_m = 0.0;
  double odom_x_m = 0.0, odom_y_m = 0.0;  ///< where it believed it was (same moment)
  /// Headings at the same moment, world frame, in (-180, 180]: the true one and the
  /// odometry's (a turn's direction and the heading error it leaves are read from these).
  double true_theta_deg = 0.0, odom_theta_deg = 0.0;
  double dist_to_goal_m = 0.0;       ///< true distance to its goal (RobotSpec::goal)
  double cycle_p50_us = 0.0;         ///< the executive's compute time per cycle (measured, not simulated)
  double cycle_p99_us = 0.0;
};

struct RunResult {
  std::uint64_t run = 0;
  std::uint64_t seed = 0;
  /// "success" when every robot finished its FSA, else the reason: "aborted (robot: why)", or
  /// "timeout (robot in 'state' waiting for 'message' from robot | not moving (pinned) | still moving; ...)"
  std::string outcome;
  double time_s = 0.0;               ///< when the last robot finished (mission completion time)
  double closest_approach_m = 0.0;   ///< smallest true centre distance between any two robots
  std::uint64_t cycles = 0;
  std::vector<RobotResult> robots;

  bool success() const { return outcome == "success"; }
};

}  // namespace p3at::team_sim
