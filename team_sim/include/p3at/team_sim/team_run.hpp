#pragma once
/// One fast-time run of a whole team: the real executive of every robot,
/// unchanged, against simulated hardware (sim::World, SimDriveBase, SimRadio),
/// on a synthetic clock. One seed makes one run, identical every time.

#include <cstdint>
#include <string>
#include <vector>

#include "p3at/protocols/mission/mission.hpp"
#include "p3at/sim/world_config.hpp"

namespace p3at::team_sim {

struct RunOptions {
  double timeout_s = 900.0;          ///< simulated seconds before a run counts as timed out
  double settle_s = 5.0;             ///< after the last robot ends, keep acknowledging this long at most
  bool log_transitions = false;      ///< executive log lines on stderr (noisy for many runs)
};

struct RobotResult {
  std::string name;
  std::string phase;                 ///< "finished", "aborted", "running" (timed out)
  std::string reason;                ///< why aborted
  double end_time_s = 0.0;           ///< when its FSA ended (or the run's end)
  double true_x_m = 0.0, true_y_m = 0.0;  ///< true final position (world frame)
  double odom_x_m = 0.0, odom_y_m = 0.0;  ///< where it believed it was
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

/// Prepared once per campaign: the world with the mission's robots placed at
/// their start poses, and each robot's final goal. Throws std::invalid_argument
/// (naming the robot) when the world has no model for a mission robot.
class TeamScenario {
 public:
  TeamScenario(mission::Mission mission, const sim::WorldConfig& world);

  const mission::Mission& mission() const { return mission_; }
  const sim::WorldConfig& world() const { return world_; }
  const std::vector<mission::Point2>& goals() const { return goals_; }

  /// Runs the team once with `seed` (deterministic).
  RunResult run(std::uint64_t run_index, std::uint64_t seed, const RunOptions& options = {}) const;

 private:
  mission::Mission mission_;
  sim::WorldConfig world_;
  std::vector<mission::Point2> goals_;
};

}  // namespace p3at::team_sim
