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

/// Robots i and j's samples in branch b, in the branch's order.
std::vector<const SeparationSample*> samples_of_pair(const Branch& b, std::size_t i, std::size_t j) {
  std::vector<const SeparationSample*> pair;
  for (const SeparationSample& s : b.separations) {
    if ((s.robot_i == i && s.robot_j == j) || (s.robot_i == j && s.robot_j == i)) pair.push_back(&s);
  }
  return pair;
}

/// Every pair's samples in branch b in one pass, at [min * n + max] for a
/// team of n (the team's curve asks all n (n - 1) / 2 pairs of each branch:
/// one pass per pair read the branch's samples 15 times for six robots).
std::vector<std::vector<const SeparationSample*>> samples_by_pair(const Branch& b, std::size_t n) {
  std::vector<std::vector<const SeparationSample*>> pairs(n * n);
  for (const SeparationSample& s : b.separations) {
    const std::size_t lo = std::min(s.robot_i, s.robot_j), hi = std::max(s.robot_i, s.robot_j);
    if (hi < n) pairs[lo * n + hi].push_back(&s);
  }
  return pairs;
}

/// The pair's kept samples cut into stretches. A run of joined samples (no
/// gap beyond the horizon) is cut every W seconds, W the shortest rigid span
/// in the run, the cuts placed so that the run's closest moment (the least
/// mean distance) is in the middle of its stretch: a pass is then taken as
/// one draw rather than split. Each stretch also holds the next stretch's
/// first sample (the segment between them is in it).
/// `pair` is the pair's samples in the branch's order (samples_of_pair).
std::vector<std::vector<Point>> stretches(const std::vector<const SeparationSample*>& pair, std::size_t i,
                                          bool* parted) {
  std::vector<std::vector<const SeparationSample*>> runs;
  for (const SeparationSample* s : pair) {
    if (s->beyond_horizon) {
      if (parted != nullptr) *parted = true;
      continue;
    }
    if (!s->joined || runs.empty()) runs.emplace_back();
    runs.back().push_back(s);
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
/// The path is made of pieces: a segment between consecutive samples
/// (close) or a sample (together), each with its own bound on how fast its
/// distance moves with z (the largest singular value of its samples' error
/// roots). Only the pieces that can decide "below d" somewhere on the grid
/// are kept: a segment (close) whose distance stays at or above d for every
/// z there, or a sample (together) whose distance stays below d, cannot
/// change which side of d the whole path is on, so leaving it out moves no
/// cell's answer. The quadrature (cell_mass) prunes the same way cell by
/// cell. Why: a stretch's error grows along it, and a pass comes close at a
/// few of its samples; with the whole stretch's bound the quadrature refined
/// a band several times too wide about d's contour (gen_7509, six robots:
/// 57,000 distances per undecided stretch).
class StretchPath {
 public:
  StretchPath(const std::vector<Point>& stretch, bool close, double d, double grid_radius)
      : stretch_(stretch), close_(close), at_(stretch.size()), placed_(stretch.size(), 0) {
    std::vector<double> gain(stretch.size());  // each sample's largest singular value
    for (std::size_t k = 0; k < stretch.size(); ++k) gain[k] = spectral_norm(stretch[k].root);
    double whole = 0.0;
    for (const double g : gain) whole = std::max(whole, g);
    const double spread = whole * grid_radius;
    const double margin = 1e-9 * (1.0 + std::abs(d));
    const auto keep = [&](std::size_t k, std::size_t last) {
      pieces_.push_back(k);
      double g = 0.0;
      for (std::size_t q = k; q <= last; ++q) g = std::max(g, gain[q]);
      gain_.push_back(g);
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
  std::size_t pieces() const { return pieces_.size(); }
  /// Nothing kept: the whole grid is on one side of d (far for close, within
  /// for staying together).
  bool decided() const { return pieces_.empty(); }
  /// Whether the path's distance is the least of its pieces' (close) rather
  /// than the greatest (together).
  bool close() const { return close_; }
  double gain(std::size_t p) const { return gain_[p]; }
  /// Piece p's distance at z; `stamp` names the point z (one per cell), so
  /// that a sample shared by two segments is placed once.
  double piece_distance(std::size_t p, const Eigen::Vector2d& z, std::size_t stamp) {
    const std::size_t k = pieces_[p];
    if (!close_ || stretch_.size() == 1) return place(k, z, stamp).norm();
    return distance_to_segment(place(k, z, stamp), place(k + 1, z, stamp));
  }

 private:
  const Eigen::Vector2d& place(std::size_t k, const Eigen::Vector2d& z, std::size_t stamp) {
    if (placed_[k] != stamp) {
      at_[k] = stretch_[k].mean + stretch_[k].root * z;
      placed_[k] = stamp;
    }
    return at_[k];
  }

  const std::vector<Point>& stretch_;
  bool close_;
  std::vector<Eigen::Vector2d> at_;
  std::vector<std::size_t> placed_;  ///< the stamp each sample of at_ was placed for
  std::vector<std::size_t> pieces_;  ///< first sample of each kept piece
  std::vector<double> gain_;         ///< each kept piece's bound
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

/// The quadrature of one stretch against one d: the pieces still able to
/// decide each cell (a stack of lists, one per level), and the stamps that
/// name the cells' centres.
struct Quadrature {
  StretchPath& path;
  double d;
  std::vector<std::vector<std::size_t>> active;  ///< [level]: the pieces that take part in a cell there
  std::vector<double> distance;                  ///< scratch: each active piece's distance at a centre
  std::size_t stamp = 0;
};

/// The mass of the z in the cell for which the path's distance is below d:
/// all of it or none where the distance at the centre decides the whole cell
/// (it moves by at most the active pieces' largest bound times the
/// half-diagonal), else the four quarters; a leaf still undecided counts by
/// its centre. The quarters are asked only with the pieces that can reach
/// the other side of d somewhere in this cell: for close, a segment at or
/// above d all over the cell cannot make the least distance fall below d
/// there; for together, a sample below d all over it cannot make the
/// greatest rise to d. So each cell's answer is the one all pieces would
/// give, and a cell far along a long stretch pays for the few segments near
/// it (gen_7610's laps: 80 % of the scoring in distance_to_segment).
double cell_mass(Quadrature& q, const Cell& c, int level) {
  const double mass = mass_of(c);
  if (!(mass > 0.0)) return 0.0;
  const std::vector<std::size_t>& active = q.active[static_cast<std::size_t>(level)];
  const bool close = q.path.close();
  if (active.empty()) return close ? 0.0 : mass;  // nothing near d: far (close) or within (together) all over
  const Eigen::Vector2d centre(0.5 * (edge(c.i0) + edge(c.i1)), 0.5 * (edge(c.j0) + edge(c.j1)));
  const double half = half_diagonal()[static_cast<std::size_t>(level)];
  const std::size_t stamp = ++q.stamp;
  double at_centre = close ? std::numeric_limits<double>::infinity() : 0.0;
  double lipschitz = 0.0;
  q.distance.resize(active.size());
  for (std::size_t a = 0; a < active.size(); ++a) {
    const double dist = q.path.piece_distance(active[a], centre, stamp);
    q.distance[a] = dist;
    at_centre = close ? std::min(at_centre, dist) : std::max(at_centre, dist);
    lipschitz = std::max(lipschitz, q.path.gain(active[a]));
  }
  const double reach = lipschitz * half;
  if (at_centre + reach < q.d) return mass;
  if (at_centre - reach >= q.d) return 0.0;
  if (level >= kLevels) return at_centre < q.d ? mass : 0.0;
  std::vector<std::size_t>& next = q.active[static_cast<std::size_t>(level) + 1];
  next.clear();
  for (std::size_t a = 0; a < active.size(); ++a) {
    const double r = q.path.gain(active[a]) * half;
    const bool decides = close ? q.distance[a] - r < q.d : q.distance[a] + r >= q.d;
    if (decides) next.push_back(active[a]);
  }
  // The quarters only write the levels below theirs: `next` holds for all four.
  const int im = (c.i0 + c.i1) / 2, jm = (c.j0 + c.j1) / 2;
  return cell_mass(q, {c.i0, im, c.j0, jm}, level + 1) + cell_mass(q, {im, c.i1, c.j0, jm}, level + 1) +
         cell_mass(q, {c.i0, im, jm, c.j1}, level + 1) + cell_mass(q, {im, c.i1, jm, c.j1}, level + 1);
}

/// Over the error z: the mass of the z for which the stretch's path comes
/// within d (close = true), or stays within d at every sample (close = false).
double stretch_mass(const std::vector<Point>& stretch, double d, bool close) {
  StretchPath path(stretch, close, d, half_diagonal()[0]);
  const Cell whole{0, kFine, 0, kFine};
  if (path.decided()) return close ? 0.0 : mass_of(whole);
  Quadrature q{path, d, std::vector<std::vector<std::size_t>>(kLevels + 1), {}, 0};
  for (std::size_t p = 0; p < path.pieces(); ++p) q.active[0].push_back(p);
  return cell_mass(q, whole, 0);
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

/// P(close somewhere) by Boole over the stretches. It stops once the sum
/// reaches 1: every caller takes 1 - max(0, 1 - it), which is then 1 however
/// many stretches follow (gen_7610's pairs that meet on every lap).
double close_mass(const std::vector<std::vector<Point>>& all, double d_m) {
  double close = 0.0;
  for (const std::vector<Point>& s : all) {
    if (close >= 1.0) break;
    close += stretch_mass(s, d_m, true) + outside_mass();
  }
  return close;
}

bool beyond_reach(double d_m) { return !(d_m <= 0.5 * kSeparationHorizonM); }

/// probability_always_apart; with `seen` (a pair's stretches -> P(close
/// somewhere), for one d), stretches met before are not integrated again.
double always_apart(const Branch& b, std::size_t i, std::size_t j, double d_m,
                    std::unordered_map<std::string, double>* seen) {
  if (beyond_reach(d_m)) return 0.0;
  if (!(d_m > 0.0)) return 1.0;
  const std::vector<std::vector<Point>> all = stretches(samples_of_pair(b, i, j), i, nullptr);
  if (seen == nullptr) return std::max(0.0, 1.0 - close_mass(all, d_m));
  const auto [at, fresh] = seen->try_emplace(stretches_key(all), 0.0);
  if (fresh) at->second = close_mass(all, d_m);
  return std::max(0.0, 1.0 - at->second);
}

/// The lightest branches whose weights sum to at most kNegligibleBranchMass,
/// marked true (ties broken by index, so the set is the same on any
/// machine). They are counted as failure without being asked: the team's
/// P(no pair within d) is then lower by at most that mass, still a lower
/// bound. Why: a patrol relieved wherever the message finds it ends in many
/// branches, most of them very light. gen_7610's 2,303 branches hold
/// 2,348,768 samples, and its 12 heaviest hold 0.99999 of the mass; asked
/// whole, its closest-approach curve ran for over an hour.
std::vector<bool> negligible_branches(const SystemOutcome& outcome) {
  const std::size_t n = outcome.branches.size();
  std::vector<std::size_t> lightest_first(n);
  for (std::size_t k = 0; k < n; ++k) lightest_first[k] = k;
  std::stable_sort(lightest_first.begin(), lightest_first.end(), [&](std::size_t a, std::size_t b) {
    return outcome.branches[a].weight < outcome.branches[b].weight;
  });
  std::vector<bool> unasked(n, false);
  double dropped = 0.0;
  for (const std::size_t k : lightest_first) {
    dropped += std::max(0.0, outcome.branches[k].weight);
    if (dropped > kNegligibleBranchMass) break;
    unasked[k] = true;
  }
  return unasked;
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
  const std::vector<std::vector<Point>> all = stretches(samples_of_pair(b, i, j), i, &parted);
  if (parted || all.empty()) return 0.0;
  double apart = 0.0;
  for (const std::vector<Point>& s : all) apart += 1.0 - stretch_mass(s, d_m, false);
  return std::max(0.0, 1.0 - apart);
}

double probability_no_pair_within(const SystemOutcome& outcome, double d_m) {
  return probability_no_pair_within(outcome, std::vector<double>{d_m}).front();
}

std::vector<double> probability_no_pair_within(const SystemOutcome& outcome, const std::vector<double>& ds) {
  // A pair's stretches -> P(close somewhere) at each of ds, NaN until asked:
  // branches that differ only in other robots' choices share it.
  std::unordered_map<std::string, std::vector<double>> seen;
  std::vector<double> total(ds.size(), 0.0), close(ds.size());
  const std::vector<bool> unasked = negligible_branches(outcome);
  for (std::size_t index = 0; index < outcome.branches.size(); ++index) {
    if (unasked[index]) continue;  // counted as failure: adds nothing
    const Branch& b = outcome.branches[index];
    const std::size_t n = b.robots.size();
    const std::vector<std::vector<const SeparationSample*>> pairs = samples_by_pair(b, n);
    std::fill(close.begin(), close.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        // The pair's stretches and their entry in seen, made at the first d that needs them.
        std::vector<std::vector<Point>> all;
        std::vector<double>* masses = nullptr;
        for (std::size_t k = 0; k < ds.size(); ++k) {
          // A branch already close at d counts 0 there whatever follows.
          if (close[k] >= 1.0) continue;
          if (beyond_reach(ds[k])) {  // always_apart's 0
            close[k] += 1.0;
            continue;
          }
          if (!(ds[k] > 0.0)) continue;  // always_apart's 1
          if (masses == nullptr) {
            all = stretches(pairs[i * n + j], i, nullptr);
            const auto [at, fresh] = seen.try_emplace(stretches_key(all));
            if (fresh) at->second.assign(ds.size(), std::numeric_limits<double>::quiet_NaN());
            masses = &at->second;
          }
          double& mass = (*masses)[k];
          if (std::isnan(mass)) mass = close_mass(all, ds[k]);
          close[k] += 1.0 - std::max(0.0, 1.0 - mass);
        }
      }
    }
    for (std::size_t k = 0; k < ds.size(); ++k) total[k] += b.weight * std::max(0.0, 1.0 - close[k]);
  }
  for (double& t : total) t = std::clamp(t, 0.0, 1.0);
  return total;
}

}  // namespace p3at::verifier
