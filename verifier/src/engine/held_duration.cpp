#include "engine/held_duration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

#include "engine/trigger_phase.hpp"

namespace p3at::verifier::engine {
namespace {

// Points per half arc between two directions. The checks are a cycle apart
// and T rarely varies by more than a few cycles over a half arc, so 16
// points resolve the shape (the peaks where T turns) well below a cycle.
constexpr std::size_t kPointsPerHalfArc = 16;
// A crossing-time spread below this (cycles) puts less than 1e-12 of the
// mass on another check unless the crossing is that close to one: kept whole.
constexpr double kMinCrossingSdCycles = 1e-4;
// An approach that has all but stalled would make the spread unbounded:
// beyond this many cycles the split is capped.
constexpr double kMaxCrossingSdCycles = 50.0;

/// The continuous crossing time, in cycles from the entry: interpolated
/// within the last cycle where the trigger was crossed by moving toward it;
/// otherwise (fired at once, or by another kind of trigger) half a cycle
/// before the check that fired, so that the check is its ceiling again.
/// The same for a probe (ProbeEnd), which records its end as a path does.
double crossing_time(std::size_t fired_at_cycles, double crossing_c) {
  const double cycles = static_cast<double>(fired_at_cycles);
  return crossing_c >= 0.0 ? cycles - 1.0 + crossing_c : cycles - 0.5;
}
double crossing_time(const FinishedPath& p) { return crossing_time(p.walker.cycles, p.crossing_c); }

double crossing_sd(double crossing_c, double sd) {
  return crossing_c >= 0.0 ? std::min(sd, kMaxCrossingSdCycles) : 0.0;
}
double crossing_sd(const FinishedPath& p) { return crossing_sd(p.crossing_c, p.crossing_sd); }

/// The slope at a node from its two secants. Where T keeps rising or
/// falling through the node, Fritsch and Carlson's harmonic mean: the
/// interpolant then never overshoots its nodes (a kink in T, where a
/// direction starts to meet an obstacle, does not ring). Where the node is a
/// turning point of the samples, the central difference: T's true extreme
/// lies between the nodes, beyond the nearest sample, and a zero slope
/// there would cut it off (T = 100 + 20 cos(phi) at 8 directions: the
/// samples reach 118.5, the interpolant 119.85, the truth 120; at the top,
/// cutting it off is the optimistic error).
/// A flat side (a zero secant) is a kink, not a turn: slope zero, so a run
/// of equal samples beside a rise stays flat instead of dipping below them.
double node_slope(double left, double right) {
  if (left * right > 0.0) return 2.0 / (1.0 / left + 1.0 / right);
  if (left * right < 0.0) return 0.5 * (left + right);
  return 0.0;
}

/// node_slope() for unequal spacing: secants `left` over `h_left` and
/// `right` over `h_right`. Rising or falling through: Fritsch and Butland's
/// weighted harmonic mean; a turn: the three-point derivative. Equal
/// spacing gives node_slope() again.
double node_slope_spaced(double left, double h_left, double right, double h_right) {
  if (left * right > 0.0) {
    const double w1 = 2.0 * h_right + h_left, w2 = h_right + 2.0 * h_left;
    return (w1 + w2) / (w1 / left + w2 / right);
  }
  if (left * right < 0.0) return (h_left * right + h_right * left) / (h_left + h_right);
  return 0.0;
}

/// The cubic Hermite interpolant on s in [0, 1] from t0 (slope m0) to t1 (slope m1).
double hermite(double t0, double m0, double t1, double m1, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * t0 + (s3 - 2.0 * s2 + s) * m0 + (-2.0 * s3 + 3.0 * s2) * t1 + (s3 - s2) * m1;
}

/// A probed circle's directions and probes in order of angle, each with
/// what it did under the first draw with respect to one exit.
struct ArcSample {
  double u = 0.0;  ///< radians from the first direction, in [0, 2 pi)
  enum Kind { kFired, kRunning, kOther } kind = kOther;
  double t = 0.0, sd = 0.0;  ///< the crossing time and its sd (cycles), when fired
};

/// The duration's mass along a probed circle's fired arcs (held_duration.hpp,
/// its last paragraph): `add(weight, T, sd)` per point, the weights
/// fractions of the circle's fired mass `mass`.
template <typename Add>
void spread_on_arcs(const HeldCircle& circle, double mass, const Add& add) {
  const std::vector<const FinishedPath*>& fired = circle.fired;
  const std::size_t n = fired.size();
  const std::vector<double>& angles = circle.probed->angles;
  const std::vector<double>& boundaries = circle.probed->boundaries;
  const double a0 = angles.front();
  const auto unwrap = [a0](double a) {
    double u = std::fmod(a - a0, kTurnRad);
    return u < 0.0 ? u + kTurnRad : u;
  };
  std::vector<ArcSample> samples;
  std::vector<std::size_t> node_of;  // sample index -> direction, or n for a probe
  for (std::size_t j = 0; j < n; ++j) {
    ArcSample a;
    a.u = unwrap(angles[j]);
    if (fired[j]) {
      a.kind = ArcSample::kFired;
      a.t = crossing_time(*fired[j]);
      a.sd = crossing_sd(*fired[j]);
    } else if (j < circle.running.size() && circle.running[j]) {
      a.kind = ArcSample::kRunning;
    }
    samples.push_back(a);
    node_of.push_back(j);
  }
  for (const ProbeEnd& p : circle.probed->probes) {
    ArcSample a;
    a.u = unwrap(p.angle_rad);
    if (p.outcome == draw_fired(circle.exit)) {
      a.kind = ArcSample::kFired;
      a.t = crossing_time(p.cycles, p.crossing_c);
      a.sd = crossing_sd(p.crossing_c, p.crossing_sd);
    } else if (p.outcome == kDrawRunning) {
      a.kind = ArcSample::kRunning;
    }
    samples.push_back(a);
    node_of.push_back(n);
  }
  std::vector<std::size_t> order(samples.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return samples[a].u < samples[b].u; });
  std::vector<ArcSample> s;
  std::vector<std::size_t> position(n, 0);  // direction -> its place in s
  for (const std::size_t i : order) {
    if (node_of[i] < n) position[node_of[i]] = s.size();
    s.push_back(samples[i]);
  }
  const std::size_t m = s.size();
  const auto step = [m](std::size_t i, int dir) { return dir > 0 ? (i + 1) % m : (i + m - 1) % m; };
  const auto distance = [&](std::size_t from, std::size_t to, int dir) {
    const double d = dir > 0 ? s[to].u - s[from].u : s[from].u - s[to].u;
    return d > 0.0 ? d : d + kTurnRad;
  };
  // The value the arc from fired sample p reaches at its neighbour on side
  // `dir`, as toward() in held_duration(): the neighbour's crossing, or for
  // a running one the later of the redraw and p's trend carried on.
  const auto toward = [&](std::size_t p, int dir) -> std::optional<double> {
    const std::size_t q = step(p, dir);
    if (s[q].kind == ArcSample::kFired) return s[q].t;
    if (s[q].kind != ArcSample::kRunning) return std::nullopt;
    const std::size_t other = step(p, -dir);
    const double trend = s[other].kind == ArcSample::kFired
                             ? (s[p].t - s[other].t) / distance(p, other, -dir) * distance(p, q, dir)
                             : 0.0;
    return std::max(circle.draw_end_cycles, s[p].t + trend);
  };
  std::vector<double> slope(m, 0.0);  // per radian, toward increasing angle
  for (std::size_t p = 0; p < m; ++p) {
    if (s[p].kind != ArcSample::kFired) continue;
    const std::optional<double> a = toward(p, -1), b = toward(p, +1);
    const double hl = distance(p, step(p, -1), -1), hr = distance(p, step(p, +1), +1);
    if (a && b) {
      slope[p] = node_slope_spaced((s[p].t - *a) / hl, hl, (*b - s[p].t) / hr, hr);
    } else if (a) {
      slope[p] = (s[p].t - *a) / hl;
    } else if (b) {
      slope[p] = (*b - s[p].t) / hr;
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (!fired[j]) continue;
    const double w = fired[j]->walker.weight / mass;
    const double u = s[position[j]].u;
    const double high = boundaries[j] - a0;
    const double low = (j == 0 ? boundaries[n - 1] - kTurnRad : boundaries[j - 1]) - a0;
    const double arc = high - low;
    if (!(arc > 0.0)) continue;
    for (const int dir : {-1, +1}) {
      const double extent = dir > 0 ? high - u : u - low;
      std::size_t p = position[j];
      double covered = 0.0;
      while (covered < extent) {
        const std::size_t q = step(p, dir);
        const double gap = distance(p, q, dir);
        const double span = std::min(gap, extent - covered);
        const std::optional<double> end = toward(p, dir);
        if (!end) {  // toward another exit or a stuck path: the rest stays at p's time
          add(w * (extent - covered) / arc, s[p].t, s[p].sd);
          break;
        }
        const bool q_fired = s[q].kind == ArcSample::kFired;
        const double m0 = dir * slope[p] * gap;
        const double m1 = q_fired ? dir * slope[q] * gap : *end - s[p].t;
        const double sd1 = q_fired ? s[q].sd : s[p].sd;
        const double part = w * span / arc / static_cast<double>(kPointsPerHalfArc);
        for (std::size_t i = 0; i < kPointsPerHalfArc; ++i) {
          const double x = span / gap * (static_cast<double>(i) + 0.5) / static_cast<double>(kPointsPerHalfArc);
          add(part, hermite(s[p].t, m0, *end, m1, x), s[p].sd + x * (sd1 - s[p].sd));
        }
        covered += span;
        if (covered < extent && !q_fired) {  // the arc runs past a sample that did not fire: held at p's time
          add(w * (extent - covered) / arc, s[p].t, s[p].sd);
          break;
        }
        p = q;
      }
    }
  }
}

}  // namespace

Mixture1 held_duration(const HeldCircle& circle, double cycle_s, std::size_t max_components) {
  const std::vector<const FinishedPath*>& fired = circle.fired;
  const std::size_t n = fired.size();
  double mass = 0.0;
  for (const FinishedPath* p : fired) {
    if (p) mass += p->walker.weight;
  }
  if (!(mass > 0.0)) return {};
  const auto running = [&](std::size_t j) { return j < circle.running.size() && circle.running[j]; };

  // The value the arc from node j reaches at neighbour k: k's own crossing
  // when it fired this exit; for a running k, the later of the redraw and
  // j's trend from its other neighbour carried one step on; none otherwise.
  const auto toward = [&](std::size_t j, std::size_t k, std::size_t other) -> std::optional<double> {
    if (fired[k]) return crossing_time(*fired[k]);
    if (!running(k)) return std::nullopt;
    const double t = crossing_time(*fired[j]);
    const double trend = fired[other] ? t - crossing_time(*fired[other]) : 0.0;
    return std::max(circle.draw_end_cycles, t + trend);
  };

  // Each fired node's slope per direction step, from the values its arcs
  // reach: both sides give node_slope, one side its secant, none zero.
  // Both arcs at a node use it, and so does each neighbour's arc toward it.
  // A probed circle's arcs are timed by spread_on_arcs() (held_duration.hpp);
  // two directions are not a circle to interpolate on, each keeps its own time.
  const bool on_arcs = n >= 3 && circle.probed != nullptr && circle.probed->boundaries.size() == n &&
                       circle.probed->angles.size() == n;
  std::vector<double> slope(n, 0.0);
  for (std::size_t j = 0; n >= 3 && !on_arcs && j < n; ++j) {
    if (!fired[j]) continue;
    const std::size_t prev = (j + n - 1) % n, next = (j + 1) % n;
    const double t = crossing_time(*fired[j]);
    const std::optional<double> a = toward(j, prev, next), b = toward(j, next, prev);
    if (a && b) {
      slope[j] = node_slope(t - *a, *b - t);
    } else if (a) {
      slope[j] = t - *a;
    } else if (b) {
      slope[j] = *b - t;
    }
  }

  // The check that fires is ceil(T) when the crossing T moves by the
  // odometry's random error, N(0, sd^2): check n with probability
  // Phi((n - T) / sd) - Phi((n - 1 - T) / sd). Without it a leg whose
  // deterministic crossing falls just before a check is one spike, where
  // validation fires at that check or the next about half the time
  // (crosscheck gen_1007, NOISE gain 0: verify 1.000 at 15.70 s, validation
  // 0.501).
  std::map<std::int64_t, double> by_check;
  const auto add = [&](double weight, double t, double sd) {
    for (const CheckShare& c : check_shares(t, sd > kMinCrossingSdCycles ? sd : 0.0)) by_check[c.check] += weight * c.share;
  };
  if (on_arcs) spread_on_arcs(circle, mass, add);
  for (std::size_t j = 0; j < n && !on_arcs; ++j) {
    const FinishedPath* p = fired[j];
    if (!p) continue;
    const double w = p->walker.weight / mass;
    const double t0 = crossing_time(*p), sd0 = crossing_sd(*p);
    if (n < 3) {  // two directions are not a circle to interpolate on
      add(w, t0, sd0);
      continue;
    }
    // The half arcs toward each neighbour: s in (0, 1/2) from this node.
    for (const int side : {-1, +1}) {
      const std::size_t k = side > 0 ? (j + 1) % n : (j + n - 1) % n;
      const std::size_t other = side > 0 ? (j + n - 1) % n : (j + 1) % n;
      const std::optional<double> end = toward(j, k, other);
      const double half = 0.5 * w;
      if (!end) {
        add(half, t0, sd0);
        continue;
      }
      const double t1 = *end;
      const double sd1 = fired[k] ? crossing_sd(*fired[k]) : sd0;
      // Hermite in s from this node (s = 0) toward the neighbour (s = 1),
      // the slopes signed along the way; toward a running neighbour the
      // secant (it has no slope of its own).
      const double m0 = side * slope[j];
      const double m1 = fired[k] ? side * slope[k] : t1 - t0;
      for (std::size_t i = 0; i < kPointsPerHalfArc; ++i) {
        const double s = 0.5 * (static_cast<double>(i) + 0.5) / static_cast<double>(kPointsPerHalfArc);
        add(half / static_cast<double>(kPointsPerHalfArc), hermite(t0, m0, t1, m1, s), sd0 + s * (sd1 - sd0));
      }
    }
  }
  // On a circle, each check's mass is a cycle-wide component (the variance
  // of a uniform over one cycle), not a spike. Spikes are what a lone
  // robot's completion is, but the sequencer races these durations against
  // teammates' and messages' (interruption bins, orderings), and there
  // spikes meeting at one check made all-or-nothing orderings: on fresh
  // gen_7666 (5 robots) the radius curve went from 0.226 to 0.443 off, and
  // to 0.202 with the width. A leg without NOISE (one direction) has one
  // deterministic path, and keeps its spikes: a check it fires at for sure.
  const double width_var = n >= 3 ? cycle_s * cycle_s / 12.0 : 0.0;
  Mixture1 m;
  for (const auto& [check, weight] : by_check) {
    m.components.push_back({weight, static_cast<double>(check) * cycle_s, width_var});
  }
  m.normalise();
  reduce(m, max_components);
  return m;
}

}  // namespace p3at::verifier::engine
