#include "p3at/verifier/separation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "p3at/verifier/mog.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::verifier {
namespace {

// The common standard-normal error z is integrated over [-kSpan, kSpan]^2,
// a quadtree of cells split in four where the path's distance at the cell's
// centre does not decide the whole cell (the distance moves by at most the
// error's root's largest singular value times the offset in z); an
// undecided cell at the last level counts by its centre (cell_mass below).
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

/// The largest singular value of a 2 x 2 matrix (how far m z moves per unit
/// of z), a hair above it so that rounding never makes it an underestimate.
double spectral_norm(const Eigen::Matrix2d& m) {
  const Eigen::Matrix2d g = m.transpose() * m;
  const double half_trace = 0.5 * (g(0, 0) + g(1, 1));
  const double det = g(0, 0) * g(1, 1) - g(0, 1) * g(1, 0);
  const double top = half_trace + std::sqrt(std::max(0.0, half_trace * half_trace - det));
  return std::sqrt(std::max(0.0, top)) * (1.0 + 1e-12);
}

/// The stretch's error as a function of z, and how far its path comes from
/// 0 (the least distance, for `close`) or goes (the greatest distance at a
/// sample, for staying together), asked against one distance d.
///
/// Only the pieces that can decide "below d" somewhere on the grid are kept:
/// a segment (close) whose distance stays at or above d for every z there,
/// or a sample (together) whose distance stays below d, cannot change which
/// side of d the whole path is on, so leaving it out moves no cell's answer.
/// The bound on how fast the distance moves with z is then the kept pieces'
/// own (their roots' largest singular value), not the whole stretch's.
/// Why both: a stretch's error grows along it, and a pass comes close at a
/// few of its samples; with the whole stretch's bound the quadrature refined
/// a band several times too wide about d's contour (gen_7509, six robots:
/// 57,000 distances per undecided stretch).
class StretchPath {
 public:
  StretchPath(const std::vector<Point>& stretch, bool close, double d, double grid_radius)
      : stretch_(stretch), close_(close), at_(stretch.size()) {
    std::vector<double> gain(stretch.size());  // each sample's largest singular value
    for (std::size_t k = 0; k < stretch.size(); ++k) gain[k] = spectral_norm(stretch[k].root);
    double whole = 0.0;
    for (const double g : gain) whole = std::max(whole, g);
    const double spread = whole * grid_radius;
    const double margin = 1e-9 * (1.0 + std::abs(d));
    const auto keep = [&](std::size_t k, std::size_t last) {
      kept_.push_back(k);
      for (std::size_t q = k; q <= last; ++q) lipschitz_ = std::max(lipschitz_, gain[q]);
    };
    if (!close_) {
      for (std::size_t k = 0; k < stretch.size(); ++k) {
        if (stretch[k].mean.norm() + spread >= d - margin) keep(k, k);
      }
    } else if (stretch.size() == 1) {
      if (stretch[0].mean.norm() - spread < d + margin) keep(0, 0);
    } else {
      for (std::size_t k = 0; k + 1 < stretch.size(); ++k) {
        if (distance_to_segment(stretch[k].mean, stretch[k + 1].mean) - spread < d + margin) keep(k, k + 1);
      }
    }
  }
  double lipschitz() const { return lipschitz_; }
  /// Nothing kept: the whole grid is on one side of d (far for close, within
  /// for staying together).
  bool decided() const { return kept_.empty(); }
  double distance(const Eigen::Vector2d& z) {
    const auto at = [&](std::size_t k) { return stretch_[k].mean + stretch_[k].root * z; };
    if (!close_) {
      double far = 0.0;
      for (const std::size_t k : kept_) far = std::max(far, at(k).norm());
      return far;
    }
    if (stretch_.size() == 1) return at(0).norm();
    double near = std::numeric_limits<double>::infinity();
    std::size_t last = stretch_.size();
    for (const std::size_t k : kept_) {
      // Consecutive kept segments share an end: place each sample once.
      if (k != last) at_[k] = at(k);
      at_[k + 1] = at(k + 1);
      last = k + 1;
      near = std::min(near, distance_to_segment(at_[k], at_[k + 1]));
    }
    return near;
  }

 private:
  const std::vector<Point>& stretch_;
  bool close_;
  std::vector<Eigen::Vector2d> at_;
  std::vector<std::size_t> kept_;
  double lipschitz_ = 0.0;
};

/// The grid is a quadtree over [-kSpan, kSpan]^2, cells halved down to
/// kLevels times (1,024 intervals across at the leaves, the spacing the
/// quadrature has always ended at: 32 cells split five times). Its edges are
/// indices of that finest spacing, each coordinate a short dyadic fraction
/// (exact in a double), so normal_cdf is read from a table.
/// Why: normal_cdf of the edges was most of the time (gen_7541 of the fresh
/// campaigns, five robots and 158 branches: its closest-approach curve ran
/// over twenty minutes, 60 % of it in erfc and exp); and starting from the
/// whole square, a region the distance decides costs one distance at the
/// level that decides it instead of one per 32 x 32 cell.
constexpr int kLevels = 10;
constexpr int kFine = 1 << kLevels;

double edge(int i) { return -kSpan + (2.0 * kSpan / kFine) * i; }

const std::vector<double>& edge_cdf() {
  static const std::vector<double> table = [] {
    std::vector<double> t(kFine + 1);
    for (int i = 0; i <= kFine; ++i) t[static_cast<std::size_t>(i)] = normal_cdf(edge(i));
    return t;
  }();
  return table;
}

/// Half of a cell's diagonal at each level (the same for every cell there).
const std::vector<double>& half_diagonal() {
  static const std::vector<double> table = [] {
    std::vector<double> t(kLevels + 1);
    for (int k = 0; k <= kLevels; ++k) {
      const double w = edge(kFine >> k) - edge(0);
      t[static_cast<std::size_t>(k)] = 0.5 * std::hypot(w, w);
    }
    return t;
  }();
  return table;
}

struct Cell {
  int i0, i1, j0, j1;  // edges, as indices into edge_cdf()
};

double mass_of(const Cell& c) {
  const std::vector<double>& cdf = edge_cdf();
  const auto at = [&](int i) { return cdf[static_cast<std::size_t>(i)]; };
  return (at(c.i1) - at(c.i0)) * (at(c.j1) - at(c.j0));
}

/// The mass of the z in the cell for which the path's distance is below d:
/// all of it or none where the distance at the centre decides the whole cell
/// (it moves by at most the Lipschitz bound times the half-diagonal), else
/// the four quarters; a leaf still undecided counts by its centre.
double cell_mass(StretchPath& path, double d, const Cell& c, int level) {
  const double mass = mass_of(c);
  if (!(mass > 0.0)) return 0.0;
  const double centre_x = 0.5 * (edge(c.i0) + edge(c.i1)), centre_y = 0.5 * (edge(c.j0) + edge(c.j1));
  const double reach = path.lipschitz() * half_diagonal()[static_cast<std::size_t>(level)];
  const double at_centre = path.distance(Eigen::Vector2d(centre_x, centre_y));
  if (at_centre + reach < d) return mass;
  if (at_centre - reach >= d) return 0.0;
  if (level >= kLevels) return at_centre < d ? mass : 0.0;
  const int im = (c.i0 + c.i1) / 2, jm = (c.j0 + c.j1) / 2;
  return cell_mass(path, d, {c.i0, im, c.j0, jm}, level + 1) + cell_mass(path, d, {im, c.i1, c.j0, jm}, level + 1) +
         cell_mass(path, d, {c.i0, im, jm, c.j1}, level + 1) + cell_mass(path, d, {im, c.i1, jm, c.j1}, level + 1);
}

/// Over the error z: the mass of the z for which the stretch's path comes
/// within d (close = true), or stays within d at every sample (close = false).
double stretch_mass(const std::vector<Point>& stretch, double d, bool close) {
  StretchPath path(stretch, close, d, half_diagonal()[0]);
  const Cell whole{0, kFine, 0, kFine};
  if (path.decided()) return close ? 0.0 : mass_of(whole);
  return cell_mass(path, d, whole, 0);
}

/// A pair's stretches as bytes: branches that differ only in other robots'
/// choices carry the same stretches for this pair, and their mass is then
/// the same number (gen_7509: a third of the stretches asked were new).
std::string stretches_key(const std::vector<std::vector<Point>>& all) {
  std::string key;
  for (const std::vector<Point>& stretch : all) {
    for (const Point& p : stretch) {
      key.append(reinterpret_cast<const char*>(p.mean.data()), sizeof(double) * 2);
      key.append(reinterpret_cast<const char*>(p.root.data()), sizeof(double) * 4);
    }
    key.push_back('|');
  }
  return key;
}

double close_mass(const std::vector<std::vector<Point>>& all, double d_m) {
  double close = 0.0;
  for (const std::vector<Point>& s : all) close += stretch_mass(s, d_m, true) + outside_mass();
  return close;
}

bool beyond_reach(double d_m) { return !(d_m <= 0.5 * kSeparationHorizonM); }

/// probability_always_apart; with `seen` (a pair's stretches -> P(close
/// somewhere), for one d), stretches met before are not integrated again.
double always_apart(const Branch& b, std::size_t i, std::size_t j, double d_m,
                    std::unordered_map<std::string, double>* seen) {
  if (beyond_reach(d_m)) return 0.0;
  if (!(d_m > 0.0)) return 1.0;
  const std::vector<std::vector<Point>> all = stretches(b, i, j, nullptr);
  if (seen == nullptr) return std::max(0.0, 1.0 - close_mass(all, d_m));
  const auto [at, fresh] = seen->try_emplace(stretches_key(all), 0.0);
  if (fresh) at->second = close_mass(all, d_m);
  return std::max(0.0, 1.0 - at->second);
}

}  // namespace

double decided_separation(double d_m, bool apart, double step_m) {
  return apart ? std::max(d_m * (1.0 + kDecisionMargin), d_m + step_m)
               : std::max(0.0, std::min(d_m * (1.0 - kDecisionMargin), d_m - step_m));
}

double probability_always_apart(const Branch& b, std::size_t i, std::size_t j, double d_m) {
  return always_apart(b, i, j, d_m, nullptr);
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
  std::unordered_map<std::string, double> seen;  // shared by the branches: one d
  double total = 0.0;
  for (const Branch& b : outcome.branches) {
    const std::size_t n = b.robots.size();
    double close = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) close += 1.0 - always_apart(b, i, j, d_m, &seen);
    }
    total += b.weight * std::max(0.0, 1.0 - close);
  }
  return std::clamp(total, 0.0, 1.0);
}

}  // namespace p3at::verifier
