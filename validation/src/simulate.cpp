// vipars simulate MISSION --world FILE [--runs N] [--seed S] [--csv FILE] [--json]
// Runs the whole team in fast time, N runs from seed S (run i uses seed S+i,
// so any run can be replayed alone), one CSV row per run. (The flags:
// apps/vipars/simulate_cli.cpp; the runs: here.)

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "p3at/common/vipars_exit.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/validation/simulate.hpp"
#include "p3at/team_sim/run_table.hpp"
#include "p3at/team_sim/team_run.hpp"

namespace p3at::vipars {
namespace {


nlohmann::json run_to_json(const team_sim::RunResult& run) {
  nlohmann::json robots = nlohmann::json::array();
  for (const auto& r : run.robots) {
    robots.push_back({{"name", r.name}, {"phase", r.phase}, {"reason", r.reason}, {"end_time_s", r.end_time_s},
                      {"true_x_m", r.true_x_m}, {"true_y_m", r.true_y_m}, {"odom_x_m", r.odom_x_m},
                      {"odom_y_m", r.odom_y_m}, {"true_theta_deg", r.true_theta_deg},
                      {"odom_theta_deg", r.odom_theta_deg}, {"dist_to_goal_m", r.dist_to_goal_m}});
  }
  return {{"run", run.run}, {"seed", run.seed}, {"outcome", run.outcome}, {"time_s", run.time_s},
          {"closest_approach_m", run.closest_approach_m}, {"robots", robots}};
}

}  // namespace

int run_simulate(const SimulateOptions& o) {
  std::optional<team_sim::TeamScenario> scenario;
  try {
    scenario.emplace(mission::load_mission_file(o.mission_file), sim::load_world_file(o.world_file));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vipars simulate: %s\n", e.what());
    return kExitBadInput;
  }
  std::ofstream csv;
  if (!o.csv_file.empty()) {
    csv.open(o.csv_file);
    if (!csv) {
      std::fprintf(stderr, "vipars simulate: cannot write %s\n", o.csv_file.c_str());
      return kExitBadInput;
    }
    csv << team_sim::csv_header(scenario->mission()) << "\n";
  }
  team_sim::RunOptions run_options;
  run_options.timeout_s = o.timeout_s;
  run_options.log_transitions = o.verbose;
  const bool progress = isatty(STDERR_FILENO) != 0 && o.runs > 1;
  const bool print_rows = !o.json && o.runs <= 20;
  if (print_rows) std::printf("%s\n", team_sim::csv_header(scenario->mission()).c_str());
  std::vector<team_sim::RunResult> results;
  results.reserve(o.runs);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < o.runs; ++i) {
    results.push_back(scenario->run(i, o.seed + i, run_options));
    const std::string row = team_sim::csv_row(results.back());
    if (csv.is_open()) csv << row << "\n";
    if (print_rows) std::printf("%s\n", row.c_str());
    if (progress && (i % 10 == 9 || i + 1 == o.runs)) {
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::fprintf(stderr, "\r%llu/%llu runs, %.0f runs/s", static_cast<unsigned long long>(i + 1),
                   static_cast<unsigned long long>(o.runs), static_cast<double>(i + 1) / secs);
    }
  }
  if (progress) std::fprintf(stderr, "\n");
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const team_sim::Summary s = team_sim::summarize(results);
  const auto& robots = scenario->mission().robots;
  if (o.json) {
    nlohmann::json j;
    j["mission"] = scenario->mission().name;
    j["runs"] = nlohmann::json::array();
    for (const auto& r : results) j["runs"].push_back(run_to_json(r));
    j["summary"] = {{"runs", s.runs}, {"successes", s.successes}, {"time_mean_s", s.time_mean_s},
                    {"time_sd_s", s.time_sd_s}, {"time_min_s", s.time_min_s}, {"time_max_s", s.time_max_s},
                    {"dist_mean_m", s.dist_mean_m}, {"dist_sd_m", s.dist_sd_m}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("\n%s: %zu runs, %zu successful (%.1f%%), %.2f s wall (%.0f runs/s)\n",
                scenario->mission().name.c_str(), s.runs, s.successes,
                s.runs ? 100.0 * static_cast<double>(s.successes) / static_cast<double>(s.runs) : 0.0, wall_s,
                static_cast<double>(s.runs) / wall_s);
    // Why runs failed (a timeout says who, in which state, and why), grouped.
    std::map<std::string, std::size_t> failures;
    for (const auto& r : results) {
      if (!r.success()) ++failures[r.outcome];
    }
    for (const auto& [outcome, count] : failures) std::printf("%zu run(s): %s\n", count, outcome.c_str());
    if (s.successes > 0) {
      std::printf("completion time: mean %.1f s, sd %.1f s, min %.1f s, max %.1f s\n", s.time_mean_s, s.time_sd_s,
                  s.time_min_s, s.time_max_s);
      for (std::size_t i = 0; i < robots.size() && i < s.dist_mean_m.size(); ++i) {
        std::printf("%s: true distance to goal mean %.2f m, sd %.2f m\n", robots[i].name.c_str(), s.dist_mean_m[i],
                    s.dist_sd_m[i]);
      }
    }
  }
  return s.successes == s.runs ? kExitOk : kExitFailed;
}

}  // namespace p3at::vipars
