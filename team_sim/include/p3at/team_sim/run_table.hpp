#pragma once
/// Writing runs out: one CSV row per run, and a summary.

#include <ostream>
#include <string>
#include <vector>

#include "p3at/protocols/mission/mission.hpp"
#include "p3at/team_sim/team_run.hpp"

namespace p3at::team_sim {

/// `run,seed,outcome,time_s,dist_<robot>_m,...,closest_approach_m`
std::string csv_header(const mission::Mission& mission);
/// The same for these robot names (a merged campaign has its robots' names, not the mission).
std::string csv_header(const std::vector<std::string>& robot_names);
/// One row matching csv_header(); text fields quoted when needed.
std::string csv_row(const RunResult& run);

/// Aggregate figures over runs.
struct Summary {
  std::size_t runs = 0;
  std::size_t successes = 0;
  double time_mean_s = 0, time_sd_s = 0, time_min_s = 0, time_max_s = 0;  ///< over successful runs
  std::vector<double> dist_mean_m, dist_sd_m;                             ///< per robot, over successful runs
};
Summary summarize(const std::vector<RunResult>& runs);

}  // namespace p3at::team_sim
