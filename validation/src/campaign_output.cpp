#include "campaign_output.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <utility>

#include "p3at/team_sim/run_table.hpp"
#include "p3at/validation/validation_json.hpp"

namespace p3at::vipars {
namespace {

// Everything a report needs, computed once.
struct Report {
  std::string mission_name;
  double threshold = 0.0;
  team_sim::EmpiricalPoint point;
  std::optional<team_sim::EmpiricalGrid> grid;
  std::vector<std::pair<std::string, std::uint64_t>> failures;  // outcome, count; most frequent first
};

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

nlohmann::ordered_json report_to_json(const Report& r, const team_sim::CampaignHeader& c) {
  ValidationSummary summary;
  summary.mission_name = r.mission_name;
  summary.threshold = r.threshold;
  summary.point = &r.point;
  summary.grid = r.grid ? &*r.grid : nullptr;
  summary.region_low = c.region_low;
  summary.region_high = c.region_high;
  summary.seed = c.seed;
  summary.world_file = c.world_file;
  summary.mission_file = c.mission_file;
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

void print_grid(const team_sim::EmpiricalGrid& g, const team_sim::CampaignHeader& c) {
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
              c.region_low, c.region_high);
  for (std::size_t a = 0; a < g.tmax.size(); ++a) {
    std::printf("%8s  ", number(g.tmax[a]).c_str());
    for (const auto& e : g.joint[a]) {
      switch (team_sim::classify(e.p, c.region_low, c.region_high)) {
        case team_sim::Region::unsuccessful: std::printf("-"); break;
        case team_sim::Region::uncertain: std::printf("?"); break;
        case team_sim::Region::successful: std::printf("+"); break;
      }
    }
    std::printf("\n");
  }
}

void print_text(const Report& r, const team_sim::CampaignHeader& c) {
  const auto& p = r.point;
  std::printf("validation of %s: %llu runs from seed %llu, %llu failed\n", r.mission_name.c_str(),
              static_cast<unsigned long long>(p.runs), static_cast<unsigned long long>(c.seed),
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
  if (r.grid) print_grid(*r.grid, c);
}

}  // namespace

std::string validation_csv_header(const std::vector<std::string>& robots) {
  std::string header = team_sim::csv_header(robots);
  for (const auto& name : robots) header += ",phase_" + name;
  return header;
}

std::string validation_csv_row(const team_sim::RunResult& run) {
  std::string row = team_sim::csv_row(run);
  for (const auto& r : run.robots) row += "," + r.phase;
  return row;
}

bool write_validation_csv(std::ostream& csv, const std::vector<std::string>& robots,
                          const std::vector<team_sim::RunResult>& runs) {
  csv << validation_csv_header(robots) << "\n";
  for (const auto& run : runs) csv << validation_csv_row(run) << "\n";
  csv.flush();
  return static_cast<bool>(csv);
}

team_sim::EmpiricalPoint print_campaign_report(const team_sim::CampaignHeader& c,
                                               const std::vector<team_sim::RunResult>& runs, bool json) {
  Report report;
  report.mission_name = c.mission_name;
  report.threshold = c.threshold;
  report.point = team_sim::empirical_at(runs, c.tmax_s, c.rmax_m);
  if (c.has_grid) report.grid = team_sim::empirical_grid(runs, c.tmax_axis, c.rmax_axis);
  report.failures = group_failures(runs);
  if (json) {
    std::cout << report_to_json(report, c).dump(2) << "\n";
  } else {
    print_text(report, c);
  }
  std::cout.flush();
  return report.point;
}

}  // namespace p3at::vipars
