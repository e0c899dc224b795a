#include "engine/trajectory_pace.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace p3at::verifier::engine {

std::vector<double> path_times_at_pace(const LegTrajectory& held, const std::vector<PathSample>& redrawn_mean) {
  // The held paths' mean position after each cycle (a path that has ended
  // stays where it ended).
  std::size_t cycles = 0;
  for (const auto& p : held.paths) cycles = std::max(cycles, p.size());
  if (cycles < 2 || redrawn_mean.size() < 2) return {};
  std::vector<Eigen::Vector2d> mean(cycles, Eigen::Vector2d::Zero());
  double total = 0.0;
  for (std::size_t j = 0; j < held.paths.size(); ++j) {
    const auto& p = held.paths[j];
    if (p.empty()) continue;
    const double w = held.weight(j);
    total += w;
    for (std::size_t n = 0; n < cycles; ++n) {
      const BaseState& q = p[std::min(n, p.size() - 1)].base;
      mean[n] += w * Eigen::Vector2d(q.x_m, q.y_m);
    }
  }
  if (!(total > 0.0)) return {};
  for (Eigen::Vector2d& m : mean) m /= total;

  std::vector<double> out;
  double from = 0.0;  // in cycles: the match never goes back
  for (std::size_t s = 0; s < redrawn_mean.size(); ++s) {
    if (redrawn_mean[s].offset_s != static_cast<double>(s)) break;  // seconds 0, 1, 2, ... only
    const Eigen::Vector2d r(redrawn_mean[s].x_m, redrawn_mean[s].y_m);
    double best = std::numeric_limits<double>::infinity(), at = from;
    // The nearest point of the mean's polyline from `from` on.
    for (auto n = static_cast<std::size_t>(std::floor(from)); n + 1 < cycles; ++n) {
      const Eigen::Vector2d a = mean[n], b = mean[n + 1];
      const Eigen::Vector2d ab = b - a;
      const double len2 = ab.squaredNorm();
      double f = len2 > 0.0 ? std::clamp((r - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      f = std::max(f, from - static_cast<double>(n));  // not before `from` on its own segment
      const double d = (a + std::min(f, 1.0) * ab - r).squaredNorm();
      if (d < best) {
        best = d;
        at = static_cast<double>(n) + std::min(f, 1.0);
      }
    }
    from = at;
    out.push_back(at * held.cycle_s);
  }
  return out.size() < 2 ? std::vector<double>{} : out;
}

std::vector<Eigen::Matrix2d> redrawn_spreads(const std::vector<PathSample>& redrawn_mean, std::size_t seconds) {
  std::vector<Eigen::Matrix2d> out;
  for (std::size_t s = 0; s < seconds && s < redrawn_mean.size(); ++s) {
    const PathSample& p = redrawn_mean[s];
    Eigen::Matrix2d c;
    c << p.var_xx, p.var_xy, p.var_xy, p.var_yy;
    out.push_back(c);
  }
  return out;
}

std::vector<Eigen::Vector2d> offsets_at_spread(const std::vector<Eigen::Vector2d>& offsets,
                                               const Eigen::Matrix2d& held_cov, const Eigen::Matrix2d& target) {
  constexpr double kLeastVarM2 = 1e-6;  // (1 mm)^2
  if (held_cov.trace() < kLeastVarM2) return offsets;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> held(held_cov + kLeastVarM2 * Eigen::Matrix2d::Identity());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> wanted(target);
  const Eigen::Matrix2d map = wanted.operatorSqrt() * held.operatorInverseSqrt();
  std::vector<Eigen::Vector2d> out;
  out.reserve(offsets.size());
  for (const Eigen::Vector2d& o : offsets) out.push_back(map * o);
  return out;
}

}  // namespace p3at::verifier::engine
