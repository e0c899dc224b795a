#include "p3at/team_sim/empirical.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "p3at/team_sim/wilson.hpp"

namespace p3at::team_sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct MeanSd {
  double mean = 0.0;
  double sd = 0.0;
};

MeanSd mean_sd(const std::vector<double>& values) {
  MeanSd m;
  if (values.empty()) return m;
  for (double v : values) m.mean += v;
  m.mean /= static_cast<double>(values.size());
  if (values.size() < 2) return m;
  double sum_sq = 0.0;
  for (double v : values) sum_sq += (v - m.mean) * (v - m.mean);
  m.sd = std::sqrt(sum_sq / static_cast<double>(values.size() - 1));
  return m;
}

// For an axis in any order: its values sorted, and where each came from.
struct SortedAxis {
  std::vector<double> values;
  std::vector<std::size_t> original;
};

SortedAxis sort_axis(const std::vector<double>& axis) {
  SortedAxis s;
  s.original.resize(axis.size());
  std::iota(s.original.begin(), s.original.end(), std::size_t{0});
  std::stable_sort(s.original.begin(), s.original.end(), [&](std::size_t a, std::size_t b) { return axis[a] < axis[b]; });
  for (std::size_t i : s.original) s.values.push_back(axis[i]);
  return s;
}

// Index of the smallest axis value >= x (so x <= values[k] for all k from
// there on); values.size() when none is (x above the axis, +inf or NaN).
std::size_t bucket(const std::vector<double>& sorted_values, double x) {
  if (std::isnan(x)) return sorted_values.size();
  return static_cast<std::size_t>(std::lower_bound(sorted_values.begin(), sorted_values.end(), x) -
                                  sorted_values.begin());
}

}  // namespace

Estimate estimate(std::uint64_t count, std::uint64_t runs) {
  Estimate e;
  e.count = count;
  e.runs = runs;
  e.p = runs == 0 ? 0.0 : static_cast<double>(count) / static_cast<double>(runs);
  const Interval ci = wilson_interval(count, runs);
  e.ci_low = ci.low;
  e.ci_high = ci.high;
  return e;
}

double completion_time_s(const RunResult& run) { return run.success() ? run.time_s : kInf; }

double worst_distance_m(const RunResult& run) {
  double worst = 0.0;
  for (const auto& r : run.robots) worst = std::isnan(r.dist_to_goal_m) ? kInf : std::max(worst, r.dist_to_goal_m);
  return worst;
}

EmpiricalPoint empirical_at(const std::vector<RunResult>& runs, double tmax_s, double rmax_m) {
  EmpiricalPoint point;
  point.tmax_s = tmax_s;
  point.rmax_m = rmax_m;
  point.runs = runs.size();
  const std::size_t robot_count = runs.empty() ? 0 : runs.front().robots.size();
  std::uint64_t time_ok = 0, radius_ok = 0, joint_ok = 0;
  std::vector<std::uint64_t> robot_ok(robot_count, 0);
  std::vector<std::vector<double>> distances(robot_count);
  std::vector<double> completion;
  for (const auto& run : runs) {
    if (!run.success()) ++point.failed_runs;
    const double t = completion_time_s(run);
    if (std::isfinite(t)) completion.push_back(t);
    const bool in_time = t <= tmax_s;
    const bool in_radius = worst_distance_m(run) <= rmax_m;
    time_ok += in_time ? 1U : 0U;
    radius_ok += in_radius ? 1U : 0U;
    joint_ok += in_time && in_radius ? 1U : 0U;
    for (std::size_t i = 0; i < robot_count && i < run.robots.size(); ++i) {
      const double d = run.robots[i].dist_to_goal_m;
      robot_ok[i] += d <= rmax_m ? 1U : 0U;
      distances[i].push_back(d);
    }
  }
  point.time = estimate(time_ok, point.runs);
  point.radius = estimate(radius_ok, point.runs);
  point.joint = estimate(joint_ok, point.runs);
  for (std::size_t i = 0; i < robot_count; ++i) {
    RobotEmpirical r;
    r.name = runs.front().robots[i].name;
    r.radius = estimate(robot_ok[i], point.runs);
    const MeanSd m = mean_sd(distances[i]);
    r.dist_mean_m = m.mean;
    r.dist_sd_m = m.sd;
    point.robots.push_back(std::move(r));
  }
  if (!completion.empty()) {
    const MeanSd m = mean_sd(completion);
    point.completion_mean_s = m.mean;
    point.completion_sd_s = m.sd;
  }
  return point;
}

Region classify(double p_joint, double low, double high) {
  if (p_joint < low) return Region::unsuccessful;
  if (p_joint >= high) return Region::successful;
  return Region::uncertain;
}

const char* to_string(Region region) {
  switch (region) {
    case Region::unsuccessful: return "unsuccessful";
    case Region::uncertain: return "uncertain";
    case Region::successful: return "successful";
  }
  return "uncertain";
}

EmpiricalGrid empirical_grid(const std::vector<RunResult>& runs, const std::vector<double>& tmax,
                             const std::vector<double>& rmax) {
  const SortedAxis ts = sort_axis(tmax);
  const SortedAxis rs = sort_axis(rmax);
  const std::size_t nt = tmax.size(), nr = rmax.size();
  // Each run lands in the cell of the smallest (tmax, rmax) it meets; a
  // cumulative sum over both sorted axes then counts, for every cell, the
  // runs meeting both criteria there. Row/column nt/nr collect the runs that
  // meet no value of that axis.
  std::vector<std::vector<std::uint64_t>> cumulative(nt + 1, std::vector<std::uint64_t>(nr + 1, 0));
  for (const auto& run : runs) {
    ++cumulative[bucket(ts.values, completion_time_s(run))][bucket(rs.values, worst_distance_m(run))];
  }
  for (std::size_t a = 0; a <= nt; ++a) {
    for (std::size_t b = 0; b <= nr; ++b) {
      if (a > 0) cumulative[a][b] += cumulative[a - 1][b];
      if (b > 0) cumulative[a][b] += cumulative[a][b - 1];
      if (a > 0 && b > 0) cumulative[a][b] -= cumulative[a - 1][b - 1];
    }
  }
  const std::uint64_t n = runs.size();
  EmpiricalGrid grid;
  grid.tmax = tmax;
  grid.rmax = rmax;
  grid.time.resize(nt);
  grid.radius.resize(nr);
  grid.joint.assign(nt, std::vector<Estimate>(nr));
  // Column nr of the cumulative table (any distance, met or not) is the time
  // marginal, row nt (any time) the radius marginal.
  for (std::size_t a = 0; a < nt; ++a) grid.time[ts.original[a]] = estimate(cumulative[a][nr], n);
  for (std::size_t b = 0; b < nr; ++b) grid.radius[rs.original[b]] = estimate(cumulative[nt][b], n);
  for (std::size_t a = 0; a < nt; ++a) {
    for (std::size_t b = 0; b < nr; ++b) grid.joint[ts.original[a]][rs.original[b]] = estimate(cumulative[a][b], n);
  }
  return grid;
}

}  // namespace p3at::team_sim
