#pragma once
/// One fast-time run of a whole team: the real executive of every robot,
/// unchanged, against simulated hardware (sim::World, SimDriveBase, SimRadio),
/// on a synthetic clock. One seed makes one run, identical every time.

#include <cstdint>
#include <string>
#include <vector>

#include "p3at/mission/mission.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/run_result.hpp"

namespace p3at::team_sim {

struct RunOptions {
  double timeout_s = 900.0;          ///< simulated seconds before a run counts as timed out
  double settle_s = 5.0;             ///< after the last robot ends, keep acknowledging this long at most
  /// After the last robot has finished, keep stepping this long at most for
  /// every robot to come to rest (its executive stopped it on entering its
  /// final state; the base brakes): the final positions recorded are where
  /// they stand still. Never past timeout_s. Not for a run with an abort,
  /// recorded where it stands when the run ends.
  double rest_s = 5.0;
  bool log_transitions = false;      ///< executive log lines on stderr (noisy for many runs)
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

  /// Runs the team once with `seed` (deterministic). A successful run's
  /// completion time is when the last robot entered its final state; its
  /// recorded poses (true and odometric) are where the robots came to rest
  /// after that (RunOptions::rest_s).
  RunResult run(std::uint64_t run_index, std::uint64_t seed, const RunOptions& options = {}) const;

 private:
  mission::Mission mission_;
  sim::WorldConfig world_;
  std::vector<mission::Point2> goals_;
};

}  // namespace p3at::team_sim
