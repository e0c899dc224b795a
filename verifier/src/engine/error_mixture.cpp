#include "engine/error_mixture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace p3at::verifier::engine {
namespace {

// A heading error weighs as the lateral error it makes over this distance
// (a leg of a few metres) when choosing which components to merge.
constexpr double kHeadingLeverM = 5.0;

const ErrorMixture& single_zero() {
  static const ErrorMixture m{ErrorComponent{}};
  return m;
}

const ErrorMixture& or_single(const ErrorMixture& m) { return m.empty() ? single_zero() : m; }

double merge_cost(const ErrorComponent& a, const ErrorComponent& b) {
  Eigen::Vector3d d = a.delta - b.delta;
  d(2) *= kHeadingLeverM;
  return a.weight * b.weight / (a.weight + b.weight) * d.squaredNorm();
}

// aligned_to_total acts only when the components' spread between them is at
// least this share of the total along its main axis, and the two axes are
// at most kMaxAlignRad apart (a small disagreement of two approximations,
// not a different shape).
constexpr double kBetweenDominates = 0.5;
constexpr double kMaxAlignRad = 20.0 * 3.14159265358979323846 / 180.0;

// Components this close (heading counted as above) are merged whatever the budget.
constexpr double kSameM = 1e-3;

double separation(const ErrorComponent& a, const ErrorComponent& b) {
  Eigen::Vector3d d = a.delta - b.delta;
  d(2) *= kHeadingLeverM;
  return d.norm();
}

ErrorComponent merged(const ErrorComponent& a, const ErrorComponent& b) {
  ErrorComponent m;
  m.weight = a.weight + b.weight;
  if (!(m.weight > 0.0)) return a;
  const double fa = a.weight / m.weight, fb = b.weight / m.weight;
  m.delta = fa * a.delta + fb * b.delta;
  const Eigen::Vector3d da = a.delta - m.delta, db = b.delta - m.delta;
  m.cov = fa * (a.cov + da * da.transpose()) + fb * (b.cov + db * db.transpose());
  return m;
}

// Many components (a redrawn NOISE's segment quadrature finishes hundreds of
// paths) are first cut down to kPreMerged by merging runs of neighbours along
// the components' principal axis (where a bimodal spread is split), so that
// the pairwise merging below stays cheap (it is cubic in the count).
constexpr std::size_t kPreMerged = 48;

void pre_merge(ErrorMixture& m) {
  if (m.size() <= kPreMerged) return;
  double total = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const ErrorComponent& c : m) {
    total += c.weight;
    centre += c.weight * c.delta;
  }
  centre /= total;
  const auto scaled = [](Eigen::Vector3d d) {
    d(2) *= kHeadingLeverM;
    return d;
  };
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (const ErrorComponent& c : m) {
    const Eigen::Vector3d d = scaled(c.delta - centre);
    s += c.weight * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s);
  const Eigen::Vector3d axis = eig.eigenvectors().col(2);  // largest eigenvalue last
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) order.emplace_back(axis.dot(scaled(m[i].delta - centre)), i);
  std::sort(order.begin(), order.end());
  ErrorMixture out;
  const std::size_t n = m.size();
  for (std::size_t g = 0; g < kPreMerged; ++g) {
    const std::size_t lo = g * n / kPreMerged, hi = (g + 1) * n / kPreMerged;
    if (lo >= hi) continue;
    ErrorComponent acc = m[order[lo].second];
    for (std::size_t i = lo + 1; i < hi; ++i) acc = merged(acc, m[order[i].second]);
    out.push_back(acc);
  }
  m = std::move(out);
}

}  // namespace

void reduce(ErrorMixture& m, std::size_t max_components) {
  m.erase(std::remove_if(m.begin(), m.end(), [](const ErrorComponent& c) { return !(c.weight > 0.0); }), m.end());
  if (m.empty()) return;
  pre_merge(m);
  const std::size_t keep = std::max<std::size_t>(1, max_components);
  while (m.size() > 1) {
    std::size_t best_i = 0, best_j = 1;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < m.size(); ++i) {
      for (std::size_t j = i + 1; j < m.size(); ++j) {
        const double c = merge_cost(m[i], m[j]);
        if (c < best) {
          best = c;
          best_i = i;
          best_j = j;
        }
      }
    }
    // Within the budget, components closer than a millimetre are one anyway
    // (perfect odometry: every path's error is the same).
    if (m.size() <= keep && separation(m[best_i], m[best_j]) >= kSameM) break;
    m[best_i] = merged(m[best_i], m[best_j]);
    m.erase(m.begin() + static_cast<std::ptrdiff_t>(best_j));
  }
  double total = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const ErrorComponent& c : m) {
    total += c.weight;
    centre += c.weight * c.delta;
  }
  if (!(total > 0.0)) {
    m.clear();
    return;
  }
  centre /= total;
  for (ErrorComponent& c : m) {
    c.weight /= total;
    c.delta -= centre;
  }
  // One component left is the mean with the whole spread: nothing kept apart.
  if (m.size() == 1) m.clear();
}

void transport(ErrorMixture& m, double dx_m, double dy_m) {
  for (ErrorComponent& c : m) {
    // e_end = Phi e_start with Phi = I + [0 0 -dy; 0 0 dx; 0 0 0].
    Eigen::Matrix3d phi = Eigen::Matrix3d::Identity();
    phi(0, 2) = -dy_m;
    phi(1, 2) = dx_m;
    c.delta = phi * c.delta;
    c.cov = phi * c.cov * phi.transpose();
  }
}

ErrorMixture convolve(const ErrorMixture& a, const ErrorMixture& b, std::size_t max_components) {
  if (a.empty()) {
    ErrorMixture out = b;
    reduce(out, max_components);
    return out;
  }
  if (b.empty()) {
    ErrorMixture out = a;
    reduce(out, max_components);
    return out;
  }
  ErrorMixture out;
  out.reserve(a.size() * b.size());
  for (const ErrorComponent& x : a) {
    for (const ErrorComponent& y : b) {
      out.push_back({x.weight * y.weight, x.delta + y.delta, x.cov + y.cov});
    }
  }
  reduce(out, max_components);
  return out;
}

ErrorMixture blend_branches(const ErrorMixture& a, const Eigen::Vector3d& mean_a, double wa, const ErrorMixture& b,
                            const Eigen::Vector3d& mean_b, double wb, std::size_t max_components) {
  const double w = wa + wb;
  if (!(w > 0.0)) return a;
  const Eigen::Vector3d mean = (wa * mean_a + wb * mean_b) / w;
  ErrorMixture out;
  for (const ErrorComponent& c : or_single(a)) out.push_back({c.weight * wa / w, c.delta + mean_a - mean, c.cov});
  for (const ErrorComponent& c : or_single(b)) out.push_back({c.weight * wb / w, c.delta + mean_b - mean, c.cov});
  reduce(out, max_components);
  return out;
}

Eigen::Matrix3d explained_cov(const ErrorMixture& m) {
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (const ErrorComponent& c : m) s += c.weight * (c.cov + c.delta * c.delta.transpose());
  return s;
}

Eigen::Matrix2d floored_psd(Eigen::Matrix2d m) {
  m = 0.5 * (m + m.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
  const Eigen::Vector2d values = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * values.asDiagonal() * eig.eigenvectors().transpose();
}

ErrorMixture aligned_to_total(const ErrorMixture& m, const Eigen::Matrix2d& total) {
  if (m.size() < 2) return m;
  Eigen::Matrix2d between = Eigen::Matrix2d::Zero();
  for (const ErrorComponent& c : m) between += c.weight * c.delta.head<2>() * c.delta.head<2>().transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> b(between), t(total);
  const double lambda = b.eigenvalues()(1), mu = t.eigenvalues()(1);
  if (!(lambda > 0.0) || !(mu > 0.0) || lambda < kBetweenDominates * mu) return m;
  const Eigen::Vector2d u = b.eigenvectors().col(1);
  Eigen::Vector2d v = t.eigenvectors().col(1);
  if (u.dot(v) < 0.0) v = -v;
  const double angle = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
  if (std::abs(angle) > kMaxAlignRad) return m;
  Eigen::Matrix2d turn;
  turn << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  // Never more spread along the axis than the total has there.
  const double stretch = std::sqrt(std::min(1.0, mu / lambda));
  const Eigen::Matrix2d shape = Eigen::Matrix2d::Identity() + (stretch - 1.0) * v * v.transpose();
  const Eigen::Matrix2d map = shape * turn;
  ErrorMixture out = m;
  for (ErrorComponent& c : out) {
    c.delta.head<2>() = map * c.delta.head<2>();
    c.cov.topLeftCorner<2, 2>() = map * c.cov.topLeftCorner<2, 2>() * map.transpose();
  }
  return out;
}

}  // namespace p3at::verifier::engine
