// vipars validate MISSION --world FILE --trials N [--jobs J] [--seed S]
//   [--tmax S] [--rmax M] [--tmax-range A:B:STEP] [--rmax-range A:B:STEP]
//   [--region-low P] [--region-high P] [--timeout S] [--json] [--csv FILE]
// (the flags: apps/vipars/validate_cli.cpp; the run: here).
// The validation campaign (the seed paper's 100 real trials, in fast time):
// the real executive against the simulated hardware, N independent runs on J
// threads, and the fraction of runs that met the criteria, on the same
// quantities and grid as `vipars verify`, with 95 % Wilson intervals.
// docs/validation.md.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "p3at/common/vipars_exit.hpp"
#include "p3at/protocols/mission/loader.hpp"
#include "p3at/validation/validate.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/team_sim/run_table.hpp"
#include "p3at/team_sim/team_run.hpp"
#include "p3at/validation/range_arg.hpp"
#include "p3at/validation/validation_json.hpp"

namespace p3at::vipars {
namespace {

using Json = nlohmann::ordered_json;  // keys in the documented order

// Every run's result is kept (a few hundred bytes) until the report: 1e6 runs
// stay well under a gigabyte, and take hours anyway.
constexpr std::uint64_t kMaxTrials = 1'000'000;
constexpr unsigned kMaxJobs = 1024;


// Everything a report needs, computed once.
struct Report {
  std::string mission_name;
  double threshold = 0.0;
  team_sim::EmpiricalPoint point;
  std::optional<team_sim::EmpiricalGrid> grid;
  std::vector<std::pair<std::string, std::uint64_t>> failures;  // outcome, count; most frequent first
};

int bad_input(const std::string& message) {
  std::fprintf(stderr, "vipars validate: %s\n", message.c_str());
  return kExitBadInput;
}

// The flags' values that the parser's own checks cannot express; the message
// says which flag and what was expected.
std::optional<std::string> check_options(const ValidateOptions& o) {
  if (o.trials < 1 || o.trials > kMaxTrials) {
    return "--trials: expected 1.." + std::to_string(kMaxTrials) + ", got " + std::to_string(o.trials);
  }
  if (o.jobs > kMaxJobs) return "--jobs: expected 0 (all cores).." + std::to_string(kMaxJobs);
  if (o.tmax_given && !(o.tmax_s > 0.0 && std::isfinite(o.tmax_s))) return "--tmax: expected seconds > 0";
  if (o.rmax_given && !(o.rmax_m > 0.0 && std::isfinite(o.rmax_m))) return "--rmax: expected metres > 0";
  if (!(o.region_low >= 0.0 && o.region_low <= o.region_high && o.region_high <= 1.0)) {
    return "--region-low/--region-high: expected 0 <= low <= high <= 1";
  }
  if (!(o.timeout_s > 0.0 && o.timeout_s <= 1e6)) return "--timeout: expected simulated seconds in (0, 1e6]";
  return std::nullopt;
}

// Outcomes of the failed runs, grouped; most frequent first, then by text,
// so the report is the same whatever order the runs finished in.
std::vector<std::pair<std::string, std::uint64_t>> group_failures(const std::vector<team_sim::RunResult>& runs) {
  std::map<std::string, std::uint64_t> counts;
  for (const auto& r : runs) {
    if (!r.success()) ++counts[r.outcome];
  }
  std::vector<std::pair<std::string, std::uint64_t>> sorted(counts.begin(), counts.end());
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return sorted;
}

// The per-run table: run_table's columns plus each robot's final phase
// ("finished", "aborted", "running" when the run timed out).
std::string validation_csv_header(const mission::Mission& mission) {
  std::string header = team_sim::csv_header(mission);
  for (const auto& r : mission.robots) header += ",phase_" + r.name;
  return header;
}

std::string validation_csv_row(const team_sim::RunResult& run) {
  std::string row = team_sim::csv_row(run);
  for (const auto& r : run.robots) row += "," + r.phase;
  return row;
}

// Progress on a terminal: a bar, runs/s and the time left, redrawn in place.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

  void update(std::uint64_t done, std::uint64_t total) {
    if (!enabled_) return;
    constexpr int kWidth = 30;
    const double secs = elapsed_s();
    const double rate = secs > 0 ? static_cast<double>(done) / secs : 0.0;
    const auto filled = static_cast<int>(static_cast<double>(kWidth) * static_cast<double>(done) /
                                         static_cast<double>(std::max<std::uint64_t>(total, 1)));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r[%s] %llu/%llu runs  %.1f runs/s  ", bar.c_str(), static_cast<unsigned long long>(done),
                 static_cast<unsigned long long>(total), rate);
    if (rate > 0 && done < total) {
      const auto left = static_cast<long long>(static_cast<double>(total - done) / rate + 0.5);
      std::fprintf(stderr, "%lld:%02lld left   ", left / 60, left % 60);
    } else {
      std::fprintf(stderr, "          ");
    }
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

Json report_to_json(const Report& r, const ValidateOptions& o) {
  ValidationSummary summary;
  summary.mission_name = r.mission_name;
  summary.threshold = r.threshold;
  summary.point = &r.point;
  summary.grid = r.grid ? &*r.grid : nullptr;
  summary.region_low = o.region_low;
  summary.region_high = o.region_high;
  summary.seed = o.seed;
  summary.world_file = o.world_file;
  summary.mission_file = o.mission_file;
  return validation_json(summary);
}

// ---- text ----

std::string number(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

void print_estimate(const std::string& label, const team_sim::Estimate& e) {
  std::printf("  %-28s %.3f  [%.3f, %.3f]  (%llu/%llu)\n", label.c_str(), e.p, e.ci_low, e.ci_high,
              static_cast<unsigned long long>(e.count), static_cast<unsigned long long>(e.runs));
}

void print_grid(const team_sim::EmpiricalGrid& g, const ValidateOptions& o) {
  std::printf("\nP(t <= tmax and every r <= rmax): rows tmax (s), columns rmax (m)\n");
  std::printf("%8s %5s |", "tmax", "P(t)");
  for (double r : g.rmax) std::printf(" %5s", number(r).c_str());
  std::printf("\n");
  for (std::size_t a = 0; a < g.tmax.size(); ++a) {
    std::printf("%8s %5.2f |", number(g.tmax[a]).c_str(), g.time[a].p);
    for (const auto& e : g.joint[a]) std::printf(" %5.2f", e.p);
    std::printf("\n");
  }
  std::printf("%8s %5s |", "P(r)", "");
  for (const auto& e : g.radius) std::printf(" %5.2f", e.p);
  std::printf("\n\nregions, columns rmax %s .. %s m as above: '-' unsuccessful (P < %g), '?' uncertain, "
              "'+' successful (P >= %g)\n",
              g.rmax.empty() ? "" : number(g.rmax.front()).c_str(), g.rmax.empty() ? "" : number(g.rmax.back()).c_str(),
              o.region_low, o.region_high);
  for (std::size_t a = 0; a < g.tmax.size(); ++a) {
    std::printf("%8s  ", number(g.tmax[a]).c_str());
    for (const auto& e : g.joint[a]) {
      switch (team_sim::classify(e.p, o.region_low, o.region_high)) {
        case team_sim::Region::unsuccessful: std::printf("-"); break;
        case team_sim::Region::uncertain: std::printf("?"); break;
        case team_sim::Region::successful: std::printf("+"); break;
      }
    }
    std::printf("\n");
  }
}

void print_text(const Report& r, const ValidateOptions& o) {
  const auto& p = r.point;
  std::printf("validation of %s: %llu runs from seed %llu, %llu failed\n", r.mission_name.c_str(),
              static_cast<unsigned long long>(p.runs), static_cast<unsigned long long>(o.seed),
              static_cast<unsigned long long>(p.failed_runs));
  for (const auto& [outcome, count] : r.failures) {
    std::printf("  %llu x %s\n", static_cast<unsigned long long>(count), outcome.c_str());
  }
  std::printf("criteria: tmax %s s, rmax %s m, threshold %s\n", number(p.tmax_s).c_str(), number(p.rmax_m).c_str(),
              number(r.threshold).c_str());
  std::printf("\n  %-28s %-5s  %-14s  %s\n", "probability", "p", "95% Wilson CI", "(runs)");
  print_estimate("P(t <= " + number(p.tmax_s) + " s)", p.time);
  print_estimate("P(every r <= " + number(p.rmax_m) + " m)", p.radius);
  print_estimate("P(both) = P(success)", p.joint);
  for (const auto& robot : p.robots) print_estimate("P(" + robot.name + " r <= " + number(p.rmax_m) + " m)", robot.radius);
  std::printf("\n");
  if (p.completion_mean_s) {
    std::printf("completion time (successful runs): mean %.1f s, sd %.1f s\n", *p.completion_mean_s,
                *p.completion_sd_s);
  }
  for (const auto& robot : p.robots) {
    std::printf("%s: true distance to goal mean %.2f m, sd %.2f m\n", robot.name.c_str(), robot.dist_mean_m,
                robot.dist_sd_m);
  }
  std::printf("P(success) %s the threshold %s\n", p.joint.p >= r.threshold ? "meets" : "is below",
              number(r.threshold).c_str());
  if (r.grid) print_grid(*r.grid, o);
}

}  // namespace

int run_validate(ValidateOptions o) {
  if (auto problem = check_options(o)) return bad_input(*problem);
  std::optional<team_sim::TeamScenario> scenario;
  try {
    scenario.emplace(mission::load_mission_file(o.mission_file), sim::load_world_file(o.world_file));
  } catch (const std::exception& e) {
    return bad_input(e.what());
  }
  const mission::Criteria& criteria = scenario->mission().criteria;
  if (!o.tmax_given) o.tmax_s = criteria.tmax_s;
  if (!o.rmax_given) o.rmax_m = criteria.rmax_m;
  std::vector<double> tmax_axis{o.tmax_s}, rmax_axis{o.rmax_m};
  for (auto [flag, text, axis] : {std::tuple{"--tmax-range", &o.tmax_range, &tmax_axis},
                                  std::tuple{"--rmax-range", &o.rmax_range, &rmax_axis}}) {
    if (text->empty()) continue;
    auto parsed = parse_range(*text);
    if (!parsed) return bad_input(std::string(flag) + ": " + parsed.error().message);
    *axis = std::move(parsed).value();
  }

  std::ofstream csv;
  if (!o.csv_file.empty()) {
    csv.open(o.csv_file);
    if (!csv) return bad_input("cannot write " + o.csv_file);
  }

  team_sim::CampaignOptions campaign;
  campaign.runs = o.trials;
  campaign.seed = o.seed;
  campaign.jobs = o.jobs;
  campaign.run.timeout_s = o.timeout_s;
  const unsigned jobs = team_sim::campaign_jobs(campaign);
  ProgressBar bar(isatty(STDERR_FILENO) != 0);
  std::vector<team_sim::RunResult> runs;
  try {
    runs = team_sim::run_campaign(*scenario, campaign,
                                  [&bar](std::uint64_t done, std::uint64_t total) { bar.update(done, total); });
  } catch (const std::exception& e) {
    // A run throws only when the simulator cannot be built from the world
    // file (e.g. radio parameters): bad input, the same for every run.
    return bad_input(e.what());
  }
  const double wall_s = bar.elapsed_s();

  if (csv.is_open()) {
    csv << validation_csv_header(scenario->mission()) << "\n";
    for (const auto& run : runs) csv << validation_csv_row(run) << "\n";
    csv.flush();
    if (!csv) return bad_input("cannot write " + o.csv_file);
  }

  Report report;
  report.mission_name = scenario->mission().name;
  report.threshold = criteria.threshold;
  report.point = team_sim::empirical_at(runs, o.tmax_s, o.rmax_m);
  if (!o.tmax_range.empty() || !o.rmax_range.empty()) report.grid = team_sim::empirical_grid(runs, tmax_axis, rmax_axis);
  report.failures = group_failures(runs);

  if (o.json) {
    std::cout << report_to_json(report, o).dump(2) << "\n";
  } else {
    print_text(report, o);
  }
  std::cout.flush();
  // One grep-able line for logs; on stderr so stdout stays identical across runs.
  std::fprintf(stderr, "vipars validate: runs=%llu failed=%llu jobs=%u wall_s=%.2f runs_per_s=%.1f\n",
               static_cast<unsigned long long>(report.point.runs),
               static_cast<unsigned long long>(report.point.failed_runs), jobs, wall_s,
               wall_s > 0 ? static_cast<double>(report.point.runs) / wall_s : 0.0);
  return report.point.failed_runs == report.point.runs ? kExitFailed : kExitOk;
}

}  // namespace p3at::vipars
