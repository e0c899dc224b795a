#include "p3at/team_sim/run_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace p3at::team_sim {
namespace {

std::string quote_csv(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string fixed(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace

std::string csv_header(const mission::Mission& mission) {
  std::vector<std::string> names;
  for (const auto& r : mission.robots) names.push_back(r.name);
  return csv_header(names);
}

std::string csv_header(const std::vector<std::string>& robot_names) {
  std::string h = "run,seed,outcome,time_s";
  for (const auto& name : robot_names) h += ",dist_" + name + "_m";
  return h + ",closest_approach_m";
}

std::string csv_row(const RunResult& run) {
  std::string row = std::to_string(run.run) + "," + std::to_string(run.seed) + "," + quote_csv(run.outcome) + "," +
                    fixed(run.time_s, 2);
  for (const auto& r : run.robots) row += "," + fixed(r.dist_to_goal_m, 4);
  return row + "," + fixed(run.closest_approach_m, 4);
}

Summary summarize(const std::vector<RunResult>& runs) {
  Summary s;
  s.runs = runs.size();
  std::vector<double> times;
  std::vector<std::vector<double>> dists;
  for (const auto& r : runs) {
    if (!r.success()) continue;
    ++s.successes;
    times.push_back(r.time_s);
    if (dists.size() < r.robots.size()) dists.resize(r.robots.size());
    for (std::size_t i = 0; i < r.robots.size(); ++i) dists[i].push_back(r.robots[i].dist_to_goal_m);
  }
  const auto mean_sd = [](const std::vector<double>& v, double& mean, double& sd) {
    mean = sd = 0;
    if (v.empty()) return;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    for (double x : v) sd += (x - mean) * (x - mean);
    sd = v.size() > 1 ? std::sqrt(sd / static_cast<double>(v.size() - 1)) : 0.0;
  };
  mean_sd(times, s.time_mean_s, s.time_sd_s);
  if (!times.empty()) {
    s.time_min_s = *std::min_element(times.begin(), times.end());
    s.time_max_s = *std::max_element(times.begin(), times.end());
  }
  for (const auto& d : dists) {
    double m = 0, sd = 0;
    mean_sd(d, m, sd);
    s.dist_mean_m.push_back(m);
    s.dist_sd_m.push_back(sd);
  }
  return s;
}

}  // namespace p3at::team_sim
