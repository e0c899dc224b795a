// The motion error z(u, t) (models.hpp: MotionError) from straight runs and
// spins with true poses at both ends.
//
// Over a whole manoeuvre the per-cycle model adds up to
//   true total = scale * odometric total + E,
//   var(E) = var_per_unit * sum|increment| + rel_var * sum(increment^2),
// so each manoeuvre is one observation (x = odometric total, y = true total)
// of a regression through the origin whose residual variance is proportional
// to a known length: weighted least squares gives the scale, the weighted
// residuals the variance's level. How that variance splits between the two
// terms is fitted on single cycles when every row has a true pose (both
// terms jointly, by maximum likelihood, with the pose readings' own noise);
// otherwise one form is chosen on the runs, which the driver makes at two
// speeds.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "p3at/common/number_format.hpp"

#include "calibration/fit_parts.hpp"

namespace p3at::verifier::calibration_detail {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// Below this spread of (sum of squares / sum of sizes) across runs, every run
// went at about one speed and the two variance forms fit equally well.
constexpr double kMinSpeedSpread = 1.5;
// The single cycles' model is Gaussian: its standardised residuals have a
// kurtosis of 3 (a standard error of sqrt(24 / n), under 0.1 for the
// thousands of cycles of a calibration; odometry counts' uniform rounding
// makes it a little less, 2.5 to 2.9 on the simulator). Far above, the data
// are off the model (rare whole-count jumps: odometry counts at a near-whole
// number of counts per cycle, below the motion's own error) and the split
// is decided on the runs instead.
constexpr double kMaxCycleKurtosis = 4.0;

double weighted_scale(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z) {
  double sxy = 0.0;
  double sxx = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    sxy += x[j] * y[j] / z[j];
    sxx += x[j] * x[j] / z[j];
  }
  return sxx > 0.0 ? sxy / sxx : 1.0;
}

// Maximum log-likelihood of residuals y - k x with variance c * z_j (c at its ML value).
double log_likelihood(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                      double k) {
  const auto n = static_cast<double>(x.size());
  double c = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) c += (y[j] - k * x[j]) * (y[j] - k * x[j]) / z[j];
  c = std::max(c / n, 1e-300);
  double ll = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) ll -= 0.5 * std::log(2.0 * std::numbers::pi * c * z[j]);
  return ll - n / 2.0;
}

// Single cycles of one manoeuvre: odometric increments z and residuals r
// (true increment - scale * odometric increment).
struct Segment {
  std::vector<double> z;
  std::vector<double> r;
};

// The per-cycle likelihood. Each cycle's residual is the motion's own error,
// variance a |z| + b z^2, independent from cycle to cycle, plus the noise of
// the two pose readings that bound the cycle: odometry counts (whole
// millimetres, 1/4096 of a turn on a P3-AT) and a motion-capture system's
// jitter sit on each reading, so they add 2 s2 to a cycle's variance and -s2
// to the covariance of neighbouring cycles (a reading ends one cycle and
// starts the next), and cancel over a manoeuvre. (Treated as an independent
// floor under each cycle, that noise made the choice between the two forms
// go wrong: per-unit for the simulator's relative error in most seeds of a
// mid-range error; docs/calibration.md.)
//
// The covariance is level * (u A + w B + g T): A = |z| / mean|z|, B = z^2 /
// mean z^2 (so u and w are the two terms' shares of the average cycle),
// T = tridiag(-1, 2, -1) per manoeuvre; u + w + g = 1, each >= 0, the level
// at its maximum-likelihood value. A tridiagonal LDL^T gives the likelihood
// in O(cycles).
class CycleLikelihood {
 public:
  explicit CycleLikelihood(std::vector<Segment> segments) : segments_(std::move(segments)) {
    double s1 = 0.0;
    double s2 = 0.0;
    for (const Segment& s : segments_) {
      for (double z : s.z) {
        s1 += std::abs(z);
        s2 += z * z;
        ++n_;
      }
    }
    mean_abs_ = n_ > 0 ? s1 / static_cast<double>(n_) : 0.0;
    mean_sq_ = n_ > 0 ? s2 / static_cast<double>(n_) : 0.0;
  }

  std::size_t cycles() const { return n_; }
  double mean_abs() const { return mean_abs_; }
  double mean_sq() const { return mean_sq_; }

  // The log-likelihood (constants dropped) at shares (u, w, g), the level profiled out.
  double operator()(double u, double w, double g, double* level = nullptr) const {
    double quad = 0.0;
    double log_det = 0.0;
    const bool ok = innovations(u, w, g, [&](double y, double d) {
      quad += y * y / d;
      log_det += std::log(d);
    });
    if (!ok) return -HUGE_VAL;
    const auto n = static_cast<double>(n_);
    const double c = std::max(quad / n, 1e-300);
    if (level) *level = c;
    return -0.5 * (n * std::log(c) + log_det + n);
  }

  // The kurtosis of the standardised residuals (the innovations y / sqrt(d)
  // of the LDL^T factorisation, independent N(0, level) under the model): 3
  // for Gaussian data.
  double kurtosis(double u, double w, double g) const {
    double m2 = 0.0;
    double m4 = 0.0;
    const bool ok = innovations(u, w, g, [&](double y, double d) {
      const double e2 = y * y / d;
      m2 += e2;
      m4 += e2 * e2;
    });
    if (!ok || !(m2 > 0.0)) return 0.0;
    const auto n = static_cast<double>(n_);
    return (m4 / n) / ((m2 / n) * (m2 / n));
  }

 private:
  // Calls f(y, d) for each cycle's innovation y and its variance d (in units
  // of the level) of the tridiagonal LDL^T; false if the covariance is singular.
  template <class F>
  bool innovations(double u, double w, double g, F&& f) const {
    if (n_ == 0 || !(mean_abs_ > 0.0) || !(mean_sq_ > 0.0)) return false;
    for (const Segment& s : segments_) {
      double d_prev = 0.0;
      double y_prev = 0.0;
      for (std::size_t i = 0; i < s.z.size(); ++i) {
        const double diag = u * std::abs(s.z[i]) / mean_abs_ + w * s.z[i] * s.z[i] / mean_sq_ + 2.0 * g;
        double d = diag;
        double y = s.r[i];
        if (i > 0) {
          const double l = -g / d_prev;
          d = diag - l * l * d_prev;
          y = s.r[i] - l * y_prev;
        }
        if (!(d > 1e-300)) return false;
        f(y, d);
        d_prev = d;
        y_prev = y;
      }
    }
    return true;
  }

  std::vector<Segment> segments_;
  std::size_t n_ = 0;
  double mean_abs_ = 0.0;
  double mean_sq_ = 0.0;
};

// Shares of the per-unit term, the relative term and the readings' noise.
struct Shares {
  double unit = 0.0;
  double rel = 0.0;
  double reading = 0.0;
  double ll = -HUGE_VAL;
};

// The maximum-likelihood shares over the simplex u + w + g = 1, u, w, g >= 0,
// with the terms not `use_unit` / `use_rel` held at 0: a grid, then a pattern
// search that moves share between two terms (an edge of the simplex is
// reached exactly, so a term the data does not support ends at 0).
Shares best_shares(const CycleLikelihood& ll, bool use_unit, bool use_rel) {
  constexpr int kGrid = 20;
  Shares best;
  for (int i = 0; i <= kGrid; ++i) {
    for (int j = 0; i + j <= kGrid; ++j) {
      const double u = use_unit ? i / static_cast<double>(kGrid) : 0.0;
      const double w = use_rel ? j / static_cast<double>(kGrid) : 0.0;
      if ((!use_unit && i > 0) || (!use_rel && j > 0)) continue;
      const double g = std::max(0.0, 1.0 - u - w);
      const double v = ll(u, w, g);
      if (v > best.ll) best = {u, w, g, v};
    }
  }
  if (!(best.ll > -HUGE_VAL)) return best;
  const bool use[3] = {use_unit, use_rel, true};
  for (double step = 0.5 / kGrid; step > 1e-6;) {
    bool moved = false;
    for (int to = 0; to < 3; ++to) {
      for (int from = 0; from < 3; ++from) {
        if (to == from || !use[to] || !use[from]) continue;
        double p[3] = {best.unit, best.rel, best.reading};
        const double amount = std::min(step, p[from]);
        if (!(amount > 0.0)) continue;
        p[from] -= amount;
        p[to] += amount;
        const double v = ll(p[0], p[1], p[2]);
        if (v > best.ll + 1e-9) {
          best = {p[0], p[1], p[2], v};
          moved = true;
        }
      }
    }
    if (!moved) step /= 2.0;
  }
  // A share within the search's last steps of 0 is 0.
  if (best.unit < 1e-5) best.unit = 0.0;
  if (best.rel < 1e-5) best.rel = 0.0;
  best.reading = std::max(0.0, 1.0 - best.unit - best.rel);
  best.ll = ll(best.unit, best.rel, best.reading);
  return best;
}

// sd and its standard error from a variance and its standard error.
void add_sd(std::vector<ParameterFit>& fits, const std::string& name, double var, double var_se, std::size_t runs,
            const std::string& unit, const std::string& note) {
  ParameterFit f;
  f.name = name;
  f.value = std::sqrt(std::max(var, 0.0));
  f.std_error = f.value > 0.0 ? var_se / (2.0 * f.value) : std::sqrt(std::max(var_se, 0.0));
  f.unit = unit;
  f.runs = runs;
  f.note = note;
  fits.push_back(f);
}

}  // namespace

ScaleFit fit_scale(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& length,
                   const std::vector<double>& length_sq, bool per_cycle, bool allow_relative,
                   const CycleIncrements& cycles) {
  const std::size_t n = x.size();
  ScaleFit out;
  // Each manoeuvre's variance is level * (unit * L + rel * Q) + reading: the
  // shape (unit, rel) from the cycles or the chosen form, the level from the
  // manoeuvres' residuals, less the end readings' own noise.
  double unit = 1.0;
  double rel = 0.0;
  double reading = 0.0;
  const std::string chosen_away = "0: the other form was chosen";
  bool split_on_cycles = false;
  std::string why_not_cycles;  // when the cycles were tried and rejected
  if (allow_relative && !cycles.empty()) {
    // Every cycle observed: the increments range from a ramp's first to the
    // cruise's, at two speeds, which tells the terms apart far better than
    // whole runs. Cycles where neither the odometry nor the truth moved
    // (the rest at a manoeuvre's end) carry nothing and are left out.
    const double k = weighted_scale(x, y, length);
    std::vector<Segment> segments;
    for (const CycleSeries& c : cycles) {
      Segment s;
      for (std::size_t i = 0; i < c.odo.size() && i < c.truth.size(); ++i) {
        if (c.odo[i] == 0.0 && c.truth[i] == 0.0) continue;
        s.z.push_back(c.odo[i]);
        s.r.push_back(c.truth[i] - k * c.odo[i]);
      }
      if (!s.z.empty()) segments.push_back(std::move(s));
    }
    const CycleLikelihood ll(std::move(segments));
    const Shares joint = best_shares(ll, true, true);
    const double kurtosis = joint.ll > -HUGE_VAL ? ll.kurtosis(joint.unit, joint.rel, joint.reading) : 0.0;
    if (!(joint.ll > -HUGE_VAL)) {
      why_not_cycles = "the single cycles could not be fitted; ";
    } else if (kurtosis > kMaxCycleKurtosis) {
      why_not_cycles = "the single cycles are off their model (kurtosis " + format_fixed(kurtosis, 1) + " of " +
                       std::to_string(ll.cycles()) + " standardised residuals); ";
    } else {
      split_on_cycles = true;
      const Shares unit_only = best_shares(ll, true, false);
      const Shares rel_only = best_shares(ll, false, true);
      double level = 0.0;
      (void)ll(joint.unit, joint.rel, joint.reading, &level);
      unit = level * joint.unit / ll.mean_abs();
      rel = level * joint.rel / ll.mean_sq();
      reading = level * joint.reading;
      if (!(unit + rel > 0.0)) rel = 1.0;  // nothing beyond the readings' noise: the level decides
      const std::string over =
          " over " + std::to_string(ll.cycles()) + " single cycles (kurtosis " + format_fixed(kurtosis, 1) + ")";
      out.unit_note = "joint fit" + over + "; without it log-likelihood " +
                      format_fixed(joint.ll - rel_only.ll, 1) + " lower";
      out.rel_note = "joint fit" + over + "; without it log-likelihood " + format_fixed(joint.ll - unit_only.ll, 1) +
                     " lower";
      out.unit_runs = n;
      out.rel_runs = n;
    }
  }
  if (split_on_cycles) {
    // done above
  } else if (!allow_relative) {
    unit = 1.0;
  } else if (!per_cycle) {
    out.unit_note = "per-unit form: the log has no per-cycle rows to tell the forms apart";
    out.rel_note = chosen_away;
    out.unit_runs = n;
  } else {
    double lo = HUGE_VAL;
    double hi = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      lo = std::min(lo, length_sq[j] / length[j]);
      hi = std::max(hi, length_sq[j] / length[j]);
    }
    bool relative = true;
    std::string note;
    if (hi < kMinSpeedSpread * lo) {
      note = "relative form: all runs at one speed cannot tell the forms apart";
    } else {
      const double ll_unit = log_likelihood(x, y, length, weighted_scale(x, y, length));
      const double ll_rel = log_likelihood(x, y, length_sq, weighted_scale(x, y, length_sq));
      relative = ll_rel >= ll_unit;
      note = std::string(relative ? "relative" : "per-unit") + " form: log-likelihood " +
             format_fixed(std::abs(ll_rel - ll_unit), 1) + " above the " + (relative ? "per-unit" : "relative") +
             " form's over the runs";
    }
    unit = relative ? 0.0 : 1.0;
    rel = relative ? 1.0 : 0.0;
    (relative ? out.rel_note : out.unit_note) = why_not_cycles + note;
    (relative ? out.unit_note : out.rel_note) = chosen_away;
    (relative ? out.rel_runs : out.unit_runs) = n;
  }
  std::vector<double> z(n);
  for (std::size_t j = 0; j < n; ++j) z[j] = unit * length[j] + rel * length_sq[j];
  out.scale = weighted_scale(x, y, z);
  double weighted_sq = 0.0;
  double sxx = 0.0;
  double sq = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double r = y[j] - out.scale * x[j];
    weighted_sq += (r * r - 2.0 * reading) / z[j];
    sxx += x[j] * x[j] / z[j];
    sq += r * r;
  }
  const double dof = static_cast<double>(n > 1 ? n - 1 : 1);
  const double level = std::max(0.0, weighted_sq / dof);
  out.unit_var = level * unit;
  out.rel_var = level * rel;
  out.unit_var_se = out.unit_var * std::sqrt(2.0 / dof);
  out.rel_var_se = out.rel_var * std::sqrt(2.0 / dof);
  out.scale_se = sxx > 0.0 ? std::sqrt(std::max(level, 1e-300) / sxx) : 0.0;
  out.residual_rms = std::sqrt(sq / static_cast<double>(n));
  // Each term's share of these runs' variance, for the report.
  double unit_total = 0.0;
  double rel_total = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    unit_total += out.unit_var * length[j];
    rel_total += out.rel_var * length_sq[j];
  }
  if (split_on_cycles && unit_total + rel_total > 0.0) {
    const auto share = [&](double part) {
      return format_fixed(100.0 * part / (unit_total + rel_total), 1) + " % of these runs' variance, ";
    };
    out.unit_note = share(unit_total) + out.unit_note;
    out.rel_note = share(rel_total) + out.rel_note;
  }
  return out;
}

MotionFit fit_motion(const std::vector<Measure>& straights, const std::vector<Measure>& spins) {
  const auto per_cycle = [](const std::vector<Measure>& ms) {
    return std::all_of(ms.begin(), ms.end(), [](const Measure& m) { return m.cycles >= 3; });
  };
  // Single cycles, when every row of every manoeuvre has a true pose.
  const auto cycles_of = [](const std::vector<Measure>& ms) {
    CycleIncrements c;
    const bool all = std::all_of(ms.begin(), ms.end(), [](const Measure& m) { return m.truth_every_row && m.cycles >= 3; });
    if (!all) return c;
    for (const Measure& m : ms) c.push_back({m.cycle_odo, m.cycle_true});
    return c;
  };
  const CycleIncrements spin_cycles = cycles_of(spins);
  const CycleIncrements straight_cycles = cycles_of(straights);
  std::vector<double> sx, sy, sl, sq;  // spins
  std::vector<double> tx, ty, tl, tq;  // straights: distance
  for (const Measure& m : spins) {
    sx.push_back(m.odo_rot_rad);
    sl.push_back(m.odo_abs_rot_rad);
    sq.push_back(m.odo_rot_sq);
  }
  for (const Measure& m : straights) {
    tx.push_back(m.odo_dist_m);
    ty.push_back(m.true_dist_m);
    tl.push_back(m.odo_abs_dist_m);
    tq.push_back(m.odo_dist_sq);
  }

  // The spins' true turn includes the drift of their (small) translation, the
  // straights' heading change the rotation of their (small) odometric turns:
  // two passes settle both.
  double drift = 0.0;
  ScaleFit rot;
  ScaleFit heading;
  std::vector<double> hy(straights.size());
  for (int pass = 0; pass < 2; ++pass) {
    sy.clear();
    for (const Measure& m : spins) sy.push_back(m.true_rot_rad - drift * m.odo_dist_m);
    rot = fit_scale(sx, sy, sl, sq, per_cycle(spins), true, spin_cycles);
    for (std::size_t j = 0; j < straights.size(); ++j) {
      hy[j] = straights[j].true_rot_rad - rot.scale * straights[j].odo_rot_rad;
    }
    heading = fit_scale(tx, hy, tl, tq, false, false);
    drift = heading.scale;
  }
  const ScaleFit trans = fit_scale(tx, ty, tl, tq, per_cycle(straights), true, straight_cycles);

  // The straights' heading residuals also hold the rotation error of their
  // odometric turns; what is left is the heading error per metre.
  double rot_part_per_m = 0.0;
  for (const Measure& m : straights) {
    rot_part_per_m += rot.variance(m.odo_abs_rot_rad, m.odo_rot_sq) / m.odo_abs_dist_m;
  }
  rot_part_per_m /= static_cast<double>(straights.size());
  const double heading_var = std::max(0.0, heading.unit_var - rot_part_per_m);

  // A spin's own forward motion (wheels whose scales differ): turning through
  // true headings theta0 .. theta0 + Theta while moving k metres per radian
  // along the heading displaces the robot by k g, g = (sin(theta0 + Theta) -
  // sin(theta0), cos(theta0) - cos(theta0 + Theta)); k by least squares over
  // the spins with true ends, then per odometric radian (times rot_scale).
  struct TurnMove {
    Eigen::Vector2d g, d;  // the unit-k displacement and the true one
  };
  std::vector<TurnMove> turns;
  double gg = 0.0, gd = 0.0;
  for (const Measure& m : spins) {
    if (!m.has_truth) continue;
    const double a = m.true_start_theta_rad, b = a + m.true_rot_rad;
    const TurnMove t{{std::sin(b) - std::sin(a), std::cos(a) - std::cos(b)}, {m.true_dx_m, m.true_dy_m}};
    gg += t.g.squaredNorm();
    gd += t.g.dot(t.d);
    turns.push_back(t);
  }
  const std::size_t turn_runs = turns.size();
  const double turn_k = gg > 1e-9 ? gd / gg : 0.0;
  double turn_sq = 0.0;
  for (const TurnMove& t : turns) turn_sq += (t.d - turn_k * t.g).squaredNorm();
  const double turn_rms = turn_runs > 0 ? std::sqrt(turn_sq / static_cast<double>(turn_runs)) : 0.0;
  const double turn_se =
      gg > 1e-9 && turn_runs > 1 ? std::sqrt(turn_sq / static_cast<double>(2 * turn_runs - 1) / gg) : 0.0;

  MotionFit out;
  MotionError& e = out.motion;
  e.trans_per_rad_m = turn_k * rot.scale;
  e.trans_scale = trans.scale;
  e.rot_scale = rot.scale;
  e.drift_rad_per_m = drift;
  e.trans_var_per_m = trans.unit_var;
  e.trans_rel_var = trans.rel_var;
  e.rot_var_per_rad = rot.unit_var;
  e.rot_rel_var = rot.rel_var;
  e.heading_var_per_m = heading_var;

  const std::size_t ns = straights.size();
  const std::size_t nr = spins.size();
  out.fits.push_back({"trans_scale", trans.scale, trans.scale_se, trans.residual_rms, "", "m", ns,
                      "true / odometric distance, straight runs"});
  add_sd(out.fits, "trans_sd_per_sqrt_m", trans.unit_var, trans.unit_var_se, trans.unit_runs, "m/sqrt(m)",
         trans.unit_note);
  add_sd(out.fits, "trans_rel_sd", trans.rel_var, trans.rel_var_se, trans.rel_runs, "", trans.rel_note);
  out.fits.push_back({"rot_scale", rot.scale, rot.scale_se, rot.residual_rms * kRadToDeg, "", "deg", nr,
                      "true / odometric rotation, spins"});
  add_sd(out.fits, "rot_sd_per_sqrt_rad", rot.unit_var, rot.unit_var_se, rot.unit_runs, "rad/sqrt(rad)",
         rot.unit_note);
  add_sd(out.fits, "rot_rel_sd", rot.rel_var, rot.rel_var_se, rot.rel_runs, "", rot.rel_note);
  out.fits.push_back({"trans_per_rad_m", e.trans_per_rad_m, turn_se * rot.scale, turn_rms, "m/rad", "m", turn_runs,
                      "true forward motion per odometric radian, spins (wheels whose scales differ)"});
  out.fits.push_back({"drift_deg_per_m", drift * kRadToDeg, heading.scale_se * kRadToDeg,
                      heading.residual_rms * kRadToDeg, "deg/m", "deg", ns,
                      "true heading change per odometric metre, straight runs"});
  add_sd(out.fits, "heading_sd_per_sqrt_m", heading_var, heading.unit_var_se, ns, "rad/sqrt(m)",
         "heading spread of the straight runs, less their rotation error");
  return out;
}

}  // namespace p3at::verifier::calibration_detail
