#include "p3at/verifier/separation.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "p3at/verifier/mog.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::verifier {
namespace {

// The common standard-normal error z is integrated over [-kSpan, kSpan]^2:
// kCells x kCells cells, each split in four, down to kMaxDepth times, where
// the path's distance at the cell's centre does not decide the whole cell
// (the distance moves by at most the error's root's norm times the offset
// in z); an undecided cell at the last depth counts by its centre.
constexpr int kCells = 32;
constexpr int kMaxDepth = 5;
constexpr double kSpan = 5.0;

// 1 - the grid's mass: the error beyond kSpan sd in either coordinate.
double outside_mass() { return 1.0 - std::pow(1.0 - 2.0 * normal_cdf(-kSpan), 2); }

// A lower-triangular square root of a 2 x 2 covariance (zero where it is not
// positive: a point or a line).
Eigen::Matrix2d root(const Eigen::Matrix2d& c) {
  Eigen::Matrix2d l = Eigen::Matrix2d::Zero();
  const double a = std::max(0.0, c(0, 0));
  if (a > 0.0) {
    l(0, 0) = std::sqrt(a);
    l(1, 0) = c(1, 0) / l(0, 0);
    l(1, 1) = std::sqrt(std::max(0.0, c(1, 1) - l(1, 0) * l(1, 0)));
  } else {
    l(1, 1) = std::sqrt(std::max(0.0, c(1, 1)));
  }
  return l;
}

double distance_to_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp(-a.dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab).norm();
}

struct Point {
  Eigen::Vector2d mean;
  Eigen::Matrix2d root;
};

/// The pair's kept samples cut into stretches. A run of joined samples (no
/// gap beyond the horizon) is cut every W seconds, W the shortest rigid span
/// in the run, the cuts placed so that the run's closest moment (the least
/// mean distance) is in the middle of its stretch: a pass is then taken as
/// one draw rather than split. Each stretch also holds the next stretch's
/// first sample (the segment between them is in it).
std::vector<std::vector<Point>> stretches(const Branch& b, std::size_t i, std::size_t j, bool* parted) {
  std::vector<std::vector<const SeparationSample*>> runs;
  for (const SeparationSample& s : b.separations) {
    const bool same = (s.robot_i == i && s.robot_j == j) || (s.robot_i == j && s.robot_j == i);
    if (!same) continue;
    if (s.beyond_horizon) {
      if (parted != nullptr) *parted = true;
      continue;
    }
    if (!s.joined || runs.empty()) runs.emplace_back();
    runs.back().push_back(&s);
  }
  std::vector<std::vector<Point>> out;
  for (const std::vector<const SeparationSample*>& run : runs) {
    double span = kSeparationWindowS;
    const SeparationSample* closest = run.front();
    for (const SeparationSample* s : run) {
      span = std::min(span, s->rigid_s);
      if (s->difference.mean.norm() < closest->difference.mean.norm()) closest = s;
    }
    span = std::max(span, 1e-3);
    const double origin = closest->time_s - 0.5 * span;
    double current = 0.0;
    for (std::size_t k = 0; k < run.size(); ++k) {
      const SeparationSample& s = *run[k];
      // i - j, whichever order the samples were taken in (the distance is the same).
      const Point p{s.robot_i == i ? s.difference.mean : Eigen::Vector2d(-s.difference.mean), root(s.difference.cov)};
      const double index = std::floor((s.time_s - origin) / span);
      if (k == 0) {
        out.push_back({p});
      } else {
        out.back().push_back(p);
        if (index != current) out.push_back({p});
      }
      current = index;
    }
    // A stretch left holding only the overlap sample repeats it: drop it.
    if (run.size() > 1 && out.back().size() == 1) out.pop_back();
  }
  return out;
}

/// The stretch's error as a function of z, and how far its path comes from
/// 0 (the least distance, for `close`) or goes (the greatest distance at a
/// sample, for staying together).
class StretchPath {
 public:
  StretchPath(const std::vector<Point>& stretch, bool close) : stretch_(stretch), close_(close), at_(stretch.size()) {
    for (const Point& p : stretch) lipschitz_ = std::max(lipschitz_, p.root.norm());
  }
  double lipschitz() const { return lipschitz_; }
  double distance(const Eigen::Vector2d& z) {
    for (std::size_t k = 0; k < stretch_.size(); ++k) at_[k] = stretch_[k].mean + stretch_[k].root * z;
    if (!close_) {
      double far = 0.0;
      for (const Eigen::Vector2d& x : at_) far = std::max(far, x.norm());
      return far;
    }
    double near = at_[0].norm();
    for (std::size_t k = 0; k + 1 < at_.size(); ++k) near = std::min(near, distance_to_segment(at_[k], at_[k + 1]));
    return near;
  }

 private:
  const std::vector<Point>& stretch_;
  bool close_;
  std::vector<Eigen::Vector2d> at_;
  double lipschitz_ = 0.0;
};

/// The mass of the z in the cell [x0, x1] x [y0, y1] for which the path's
/// distance is below d.
double cell_mass(StretchPath& path, double d, double x0, double x1, double y0, double y1, int depth) {
  const double mass = (normal_cdf(x1) - normal_cdf(x0)) * (normal_cdf(y1) - normal_cdf(y0));
  if (!(mass > 0.0)) return 0.0;
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const double reach = path.lipschitz() * 0.5 * std::hypot(x1 - x0, y1 - y0);
  const double at_centre = path.distance(Eigen::Vector2d(cx, cy));
  if (at_centre + reach < d) return mass;
  if (at_centre - reach >= d) return 0.0;
  if (depth >= kMaxDepth) return at_centre < d ? mass : 0.0;
  return cell_mass(path, d, x0, cx, y0, cy, depth + 1) + cell_mass(path, d, cx, x1, y0, cy, depth + 1) +
         cell_mass(path, d, x0, cx, cy, y1, depth + 1) + cell_mass(path, d, cx, x1, cy, y1, depth + 1);
}

/// Over the error z: the mass of the z for which the stretch's path comes
/// within d (close = true), or stays within d at every sample (close = false).
double stretch_mass(const std::vector<Point>& stretch, double d, bool close) {
  StretchPath path(stretch, close);
  const double width = 2.0 * kSpan / kCells;
  double mass = 0.0;
  for (int u = 0; u < kCells; ++u) {
    for (int v = 0; v < kCells; ++v) {
      const double x0 = -kSpan + width * u, y0 = -kSpan + width * v;
      mass += cell_mass(path, d, x0, x0 + width, y0, y0 + width, 0);
    }
  }
  return mass;
}

bool beyond_reach(double d_m) { return !(d_m <= 0.5 * kSeparationHorizonM); }

}  // namespace

double decided_separation(double d_m, bool apart, double step_m) {
  return apart ? std::max(d_m * (1.0 + kDecisionMargin), d_m + step_m)
               : std::max(0.0, std::min(d_m * (1.0 - kDecisionMargin), d_m - step_m));
}

double probability_always_apart(const Branch& b, std::size_t i, std::size_t j, double d_m) {
  if (beyond_reach(d_m)) return 0.0;
  if (!(d_m > 0.0)) return 1.0;
  double close = 0.0;
  for (const std::vector<Point>& s : stretches(b, i, j, nullptr)) close += stretch_mass(s, d_m, true) + outside_mass();
  return std::max(0.0, 1.0 - close);
}

double probability_always_within(const Branch& b, std::size_t i, std::size_t j, double d_m) {
  if (beyond_reach(d_m)) return 0.0;
  bool parted = false;
  const std::vector<std::vector<Point>> all = stretches(b, i, j, &parted);
  if (parted || all.empty()) return 0.0;
  double apart = 0.0;
  for (const std::vector<Point>& s : all) apart += 1.0 - stretch_mass(s, d_m, false);
  return std::max(0.0, 1.0 - apart);
}

double probability_no_pair_within(const SystemOutcome& outcome, double d_m) {
  double total = 0.0;
  for (const Branch& b : outcome.branches) {
    const std::size_t n = b.robots.size();
    double close = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) close += 1.0 - probability_always_apart(b, i, j, d_m);
    }
    total += b.weight * std::max(0.0, 1.0 - close);
  }
  return std::clamp(total, 0.0, 1.0);
}

}  // namespace p3at::verifier
