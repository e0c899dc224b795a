#include "engine/interruption.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "engine/error_mixture.hpp"
#include "engine/trajectory_pace.hpp"
#include "p3at/executive/frames.hpp"

namespace p3at::verifier::engine {
namespace {

// Below this spread of positions over τ the interruption is one bin: the
// robot stands still (or τ is sure) and splitting would only cost branches.
constexpr double kOneBinSpreadM = 0.02;

BaseState lerp(const BaseState& a, const BaseState& b, double f) {
  BaseState out;
  out.x_m = a.x_m + f * (b.x_m - a.x_m);
  out.y_m = a.y_m + f * (b.y_m - a.y_m);
  out.theta_rad = a.theta_rad + f * (b.theta_rad - a.theta_rad);
  out.trans_mps = a.trans_mps + f * (b.trans_mps - a.trans_mps);
  out.rot_radps = a.rot_radps + f * (b.rot_radps - a.rot_radps);
  return out;
}

/// Weighted offsets as as many equally likely ones (the sequencer's spread
/// points are equally likely): slabs of equal probability along their
/// principal axis, each slab's mean. Equal weights are kept as they are.
std::vector<Eigen::Vector2d> equal_weight_offsets(const std::vector<Eigen::Vector2d>& points,
                                                  const std::vector<double>& weights) {
  const std::size_t n = points.size();
  if (n == 0) return {};
  const bool equal = std::all_of(weights.begin(), weights.end(),
                                 [&](double w) { return std::abs(w - weights.front()) <= 1e-12 * std::max(1.0, w); });
  if (equal) return points;
  double total = 0.0;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t j = 0; j < n; ++j) {
    total += weights[j];
    cov += weights[j] * points[j] * points[j].transpose();
  }
  if (!(total > 0.0)) return points;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d axis = eig.eigenvectors().col(1);
  std::vector<std::size_t> order(n);
  for (std::size_t j = 0; j < n; ++j) order[j] = j;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return points[a].dot(axis) < points[b].dot(axis); });
  const double slab = total / static_cast<double>(n);
  std::vector<Eigen::Vector2d> sums(n, Eigen::Vector2d::Zero());
  std::vector<double> masses(n, 0.0);
  double c0 = 0.0;
  for (const std::size_t j : order) {
    const double c1 = c0 + weights[j];
    for (std::size_t k = 0; k < n; ++k) {
      const double overlap = std::min(c1, static_cast<double>(k + 1) * slab) - std::max(c0, static_cast<double>(k) * slab);
      if (overlap > 0.0) {
        sums[k] += overlap * points[j];
        masses[k] += overlap;
      }
    }
    c0 = c1;
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t k = 0; k < n; ++k) out.push_back(masses[k] > 0.0 ? Eigen::Vector2d(sums[k] / masses[k]) : Eigen::Vector2d::Zero());
  return out;
}

}  // namespace

std::shared_ptr<const LegTrajectory> trajectory_subset(const LegTrajectory& leg, bool stuck) {
  auto out = std::make_shared<LegTrajectory>();
  out->cycle_s = leg.cycle_s;
  out->path_time_s = leg.path_time_s;
  double total = 0.0;
  for (std::size_t j = 0; j < leg.paths.size(); ++j) {
    if (leg.is_stuck(j) != stuck || leg.paths[j].empty()) continue;
    out->paths.push_back(leg.paths[j]);
    out->weights.push_back(leg.weight(j));
    out->stuck.push_back(stuck ? 1 : 0);
    total += leg.weight(j);
  }
  if (out->paths.empty() || total <= 0.0) return nullptr;
  for (double& w : out->weights) w /= total;
  return out;
}

std::shared_ptr<const LegTrajectory> trajectory_getting_through(const LegTrajectory& leg, double escaped) {
  const double scale = std::clamp(escaped, 0.0, 1.0);
  auto out = std::make_shared<LegTrajectory>();
  out->cycle_s = leg.cycle_s;
  out->path_time_s = leg.path_time_s;
  double total = 0.0;
  for (std::size_t j = 0; j < leg.paths.size(); ++j) {
    const double w = leg.weight(j) * (leg.is_stuck(j) ? scale : 1.0);
    if (!(w > 0.0) || leg.paths[j].empty()) continue;
    out->paths.push_back(leg.paths[j]);
    out->weights.push_back(w);
    out->stuck.push_back(leg.is_stuck(j) ? 1 : 0);
    total += w;
  }
  if (out->paths.empty() || total <= 0.0) return nullptr;
  for (double& w : out->weights) w /= total;
  return out;
}

TrajectoryPoint pose_at(const LegTrajectory& leg, std::size_t path, double t_s) {
  const std::vector<TrajectoryPoint>& p = leg.paths.at(path);
  if (p.empty()) return {};
  const double n = std::max(0.0, leg.path_time(t_s) / leg.cycle_s);
  const double last = static_cast<double>(p.size() - 1);
  if (n >= last) return p.back();
  const std::size_t i = static_cast<std::size_t>(std::floor(n));
  const double f = n - static_cast<double>(i);
  TrajectoryPoint out;
  out.base = lerp(p[i].base, p[i + 1].base, f);
  out.error.mean = p[i].error.mean + f * (p[i + 1].error.mean - p[i].error.mean);
  out.error.cov = p[i].error.cov + f * (p[i + 1].error.cov - p[i].error.cov);
  return out;
}

void truncated_moments(const Mixture1& x, double lo, double hi, double& probability, double& mean, double& var) {
  double mass = 0.0, m1 = 0.0, m2 = 0.0;
  for (const Component1& c : x.components) {
    if (!(c.weight > 0.0)) continue;
    if (!(c.var > 0.0)) {
      if (c.mean > lo && c.mean <= hi) {
        mass += c.weight;
        m1 += c.weight * c.mean;
        m2 += c.weight * c.mean * c.mean;
      }
      continue;
    }
    const double s = std::sqrt(c.var);
    const double a = std::isfinite(lo) ? (lo - c.mean) / s : -std::numeric_limits<double>::infinity();
    const double b = std::isfinite(hi) ? (hi - c.mean) / s : std::numeric_limits<double>::infinity();
    const double z = normal_cdf(b) - normal_cdf(a);
    if (!(z > 1e-15)) continue;
    const double pa = std::isfinite(a) ? normal_pdf(a) : 0.0;
    const double pb = std::isfinite(b) ? normal_pdf(b) : 0.0;
    const double apa = std::isfinite(a) ? a * pa : 0.0;
    const double bpb = std::isfinite(b) ? b * pb : 0.0;
    const double mu = c.mean + s * (pa - pb) / z;
    const double v = c.var * std::max(0.0, 1.0 + (apa - bpb) / z - ((pa - pb) / z) * ((pa - pb) / z));
    mass += c.weight * z;
    m1 += c.weight * z * mu;
    m2 += c.weight * z * (v + mu * mu);
  }
  const double total = [&] {
    double t = 0.0;
    for (const Component1& c : x.components) t += std::max(c.weight, 0.0);
    return t;
  }();
  probability = total > 0.0 ? mass / total : 0.0;
  if (mass > 0.0) {
    mean = m1 / mass;
    var = std::max(0.0, m2 / mass - mean * mean);
  } else {
    mean = var = 0.0;
  }
}

double mixture_quantile(const Mixture1& x, double p) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Component1& c : x.components) {
    const double reach = 9.0 * std::sqrt(std::max(c.var, 0.0));
    lo = std::min(lo, c.mean - reach);
    hi = std::max(hi, c.mean + reach);
  }
  if (!(lo <= hi)) return 0.0;
  for (int i = 0; i < 100 && hi - lo > 1e-9 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    if (x.cdf(mid) < p) lo = mid;
    else hi = mid;
  }
  return hi;
}

std::vector<InterruptionBin> interruption_bins(const LegTrajectory& leg, const Mixture1& tau_s, std::size_t max_bins) {
  std::vector<InterruptionBin> out;
  const std::size_t paths = leg.paths.size();
  if (paths == 0 || tau_s.components.empty()) return out;

  // How far the robot moves over τ's spread decides whether one bin will do.
  const double mean = tau_s.mean(), sd = std::sqrt(std::max(0.0, tau_s.variance()));
  double moved = 0.0;
  for (std::size_t j = 0; j < paths; ++j) {
    const BaseState a = pose_at(leg, j, mean - sd).base, b = pose_at(leg, j, mean + sd).base;
    moved = std::max(moved, std::hypot(b.x_m - a.x_m, b.y_m - a.y_m));
  }
  const std::size_t bins = moved < kOneBinSpreadM ? 1 : std::max<std::size_t>(1, max_bins);

  double edge = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < bins; ++k) {
    const double next = k + 1 == bins ? std::numeric_limits<double>::infinity()
                                      : mixture_quantile(tau_s, static_cast<double>(k + 1) / static_cast<double>(bins));
    InterruptionBin bin;
    truncated_moments(tau_s, edge, next, bin.probability, bin.tau_mean_s, bin.tau_var_s2);
    edge = next;
    if (!(bin.probability > 0.0)) continue;
    std::vector<ErrorState> errors;
    Eigen::Vector2d mean_xy = Eigen::Vector2d::Zero();
    std::vector<Eigen::Vector2d> points;
    std::vector<double> headings;
    BaseState avg;
    // Headings averaged within pi of path 0's (paths that turned around in
    // opposite directions are a whole turn apart as continuous angles).
    const double ref_theta = pose_at(leg, 0, bin.tau_mean_s).base.theta_rad;
    std::vector<double> ws(paths);
    for (std::size_t j = 0; j < paths; ++j) {
      const double w = leg.weight(j);
      ws[j] = w;
      TrajectoryPoint p = pose_at(leg, j, bin.tau_mean_s);
      p.base.theta_rad = ref_theta + exec::wrap_angle_rad(p.base.theta_rad - ref_theta);
      errors.push_back(p.error);
      points.emplace_back(p.base.x_m, p.base.y_m);
      headings.push_back(p.base.theta_rad);
      mean_xy += w * points.back();
      avg.x_m += w * p.base.x_m;
      avg.y_m += w * p.base.y_m;
      avg.theta_rad += w * p.base.theta_rad;
      avg.trans_mps += w * p.base.trans_mps;
      avg.rot_radps += w * p.base.rot_radps;
      // The motion within the bin: the path's velocity over one cycle each side.
      const BaseState before = pose_at(leg, j, bin.tau_mean_s - leg.cycle_s).base;
      const BaseState after = pose_at(leg, j, bin.tau_mean_s + leg.cycle_s).base;
      const Eigen::Vector2d v((after.x_m - before.x_m) / (2.0 * leg.cycle_s), (after.y_m - before.y_m) / (2.0 * leg.cycle_s));
      bin.within += w * v * v.transpose() * bin.tau_var_s2;
    }
    bin.base = avg;
    bin.error = combine(errors.data(), ws.data(), paths);
    for (std::size_t j = 0; j < paths; ++j) {
      bin.path_offsets.push_back(points[j] - mean_xy);
      bin.weights.push_back(ws[j]);
      bin.headings.push_back(headings[j]);
      bin.spread += ws[j] * (points[j] - mean_xy) * (points[j] - mean_xy).transpose();
    }
    if (!leg.redrawn_cov_m2.empty()) {
      // Held paths under a redrawn NOISE: their offsets at the redrawn
      // spread (leg_trajectory.hpp); what the points cannot show of it (an
      // axis they do not spread along) joins the spread within the bin.
      const Eigen::Matrix2d target = leg.redrawn_cov(bin.tau_mean_s);
      bin.path_offsets = offsets_at_spread(bin.path_offsets, bin.spread, target);
      bin.spread.setZero();
      for (std::size_t j = 0; j < paths; ++j) bin.spread += ws[j] * bin.path_offsets[j] * bin.path_offsets[j].transpose();
      bin.within += floored_psd(target - bin.spread);
    }
    bin.offsets = equal_weight_offsets(bin.path_offsets, bin.weights);
    out.push_back(std::move(bin));
  }
  return out;
}

}  // namespace p3at::verifier::engine
