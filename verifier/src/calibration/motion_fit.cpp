// The motion error z(u, t) (models.hpp: MotionError) from straight runs and
// spins with true poses at both ends.
//
// Over a whole manoeuvre the per-cycle model adds up to
//   true total = scale * odometric total + E,
//   var(E) = var_per_unit * sum|increment|  or  rel_var * sum(increment^2),
// so each manoeuvre is one observation (x = odometric total, y = true total)
// of a regression through the origin whose residual variance is proportional
// to a known length: weighted least squares gives the scale, the weighted
// residuals the variance. Which of the two variance forms applies is decided
// on single cycles when every row has a true pose (a ramp's small increments
// against the cruise's large ones), else on the runs, which the driver makes
// at two speeds: the form with the higher likelihood wins.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "p3at/common/number_format.hpp"

#include "calibration/fit_parts.hpp"

namespace p3at::verifier::calibration_detail {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// Below this spread of (sum of squares / sum of sizes) across runs, every run
// went at about one speed and the two variance forms fit equally well.
constexpr double kMinSpeedSpread = 1.5;

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

// The best log-likelihood (constants dropped) of residuals whose variance is
// s * (1 + rho * z_i), over s and rho >= 0: a floor (the measuring's own
// noise: odometry counts, a motion-capture system's jitter) plus a term
// growing with z. Profiled over rho on a grid fine enough to compare forms.
double floor_plus_form_log_likelihood(const std::vector<double>& r2, const std::vector<double>& z) {
  std::vector<double> positive;
  for (double v : z) {
    if (v > 0.0) positive.push_back(v);
  }
  if (positive.empty()) return -HUGE_VAL;
  std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(positive.size() / 2), positive.end());
  const double z_mid = positive[positive.size() / 2];
  const auto n = static_cast<double>(r2.size());
  double best = -HUGE_VAL;
  for (int step = -1; step <= 48; ++step) {
    const double rho = step < 0 ? 0.0 : std::pow(10.0, -3.0 + 0.25 * step) / z_mid;
    double s = 0.0;
    double log_sum = 0.0;
    for (std::size_t i = 0; i < r2.size(); ++i) {
      const double f = 1.0 + rho * z[i];
      s += r2[i] / f;
      log_sum += std::log(f);
    }
    s = std::max(s / n, 1e-300);
    best = std::max(best, -0.5 * (n * std::log(s) + log_sum));
  }
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
  if (!allow_relative) {
    out.relative = false;
  } else if (!cycles.odo.empty()) {
    // Every cycle observed: the increments range from a ramp's first to the
    // cruise's, which tells the forms apart far better than whole runs.
    const double k = weighted_scale(x, y, length);
    std::vector<double> r2, unit, rel;
    for (std::size_t i = 0; i < cycles.odo.size(); ++i) {
      const double r = cycles.truth[i] - k * cycles.odo[i];
      r2.push_back(r * r);
      unit.push_back(std::abs(cycles.odo[i]));
      rel.push_back(cycles.odo[i] * cycles.odo[i]);
    }
    const double ll_unit = floor_plus_form_log_likelihood(r2, unit);
    const double ll_rel = floor_plus_form_log_likelihood(r2, rel);
    out.relative = ll_rel >= ll_unit;
    out.form_note = std::string(out.relative ? "relative" : "per-unit") + " form: log-likelihood " +
                    format_fixed(std::abs(ll_rel - ll_unit), 1) + " above the " + (out.relative ? "per-unit" : "relative") +
                    " form's over " + std::to_string(cycles.odo.size()) + " single cycles";
  } else if (!per_cycle) {
    out.relative = false;
    out.form_note = "per-unit form: the log has no per-cycle rows to tell the forms apart";
  } else {
    double lo = HUGE_VAL;
    double hi = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      lo = std::min(lo, length_sq[j] / length[j]);
      hi = std::max(hi, length_sq[j] / length[j]);
    }
    if (hi < kMinSpeedSpread * lo) {
      out.relative = true;
      out.form_note = "relative form: all runs at one speed cannot tell the forms apart";
    } else {
      const double ll_unit = log_likelihood(x, y, length, weighted_scale(x, y, length));
      const double ll_rel = log_likelihood(x, y, length_sq, weighted_scale(x, y, length_sq));
      out.relative = ll_rel >= ll_unit;
      out.form_note = std::string(out.relative ? "relative" : "per-unit") + " form: log-likelihood " +
                      format_fixed(std::abs(ll_rel - ll_unit), 1) + " above the " + (out.relative ? "per-unit" : "relative") +
                      " form's";
    }
  }
  const std::vector<double>& z = out.relative ? length_sq : length;
  out.scale = weighted_scale(x, y, z);
  double weighted_sq = 0.0;
  double sxx = 0.0;
  double sq = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double r = y[j] - out.scale * x[j];
    weighted_sq += r * r / z[j];
    sxx += x[j] * x[j] / z[j];
    sq += r * r;
  }
  const double dof = static_cast<double>(n > 1 ? n - 1 : 1);
  out.variance = weighted_sq / dof;
  out.variance_se = out.variance * std::sqrt(2.0 / dof);
  out.scale_se = sxx > 0.0 ? std::sqrt(out.variance / sxx) : 0.0;
  out.residual_rms = std::sqrt(sq / static_cast<double>(n));
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
    for (const Measure& m : ms) {
      c.odo.insert(c.odo.end(), m.cycle_odo.begin(), m.cycle_odo.end());
      c.truth.insert(c.truth.end(), m.cycle_true.begin(), m.cycle_true.end());
    }
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
    const double rot_var = rot.relative ? rot.variance * m.odo_rot_sq : rot.variance * m.odo_abs_rot_rad;
    rot_part_per_m += rot_var / m.odo_abs_dist_m;
  }
  rot_part_per_m /= static_cast<double>(straights.size());
  const double heading_var = std::max(0.0, heading.variance - rot_part_per_m);

  MotionFit out;
  MotionError& e = out.motion;
  e.trans_scale = trans.scale;
  e.rot_scale = rot.scale;
  e.drift_rad_per_m = drift;
  e.trans_var_per_m = trans.relative ? 0.0 : trans.variance;
  e.trans_rel_var = trans.relative ? trans.variance : 0.0;
  e.rot_var_per_rad = rot.relative ? 0.0 : rot.variance;
  e.rot_rel_var = rot.relative ? rot.variance : 0.0;
  e.heading_var_per_m = heading_var;

  const std::size_t ns = straights.size();
  const std::size_t nr = spins.size();
  out.fits.push_back({"trans_scale", trans.scale, trans.scale_se, trans.residual_rms, "", "m", ns,
                      "true / odometric distance, straight runs"});
  const std::string unused = "0: the other form was chosen";
  add_sd(out.fits, "trans_sd_per_sqrt_m", e.trans_var_per_m, trans.relative ? 0.0 : trans.variance_se,
         trans.relative ? 0 : ns, "m/sqrt(m)", trans.relative ? unused : trans.form_note);
  add_sd(out.fits, "trans_rel_sd", e.trans_rel_var, trans.relative ? trans.variance_se : 0.0,
         trans.relative ? ns : 0, "", trans.relative ? trans.form_note : unused);
  out.fits.push_back({"rot_scale", rot.scale, rot.scale_se, rot.residual_rms * kRadToDeg, "", "deg", nr,
                      "true / odometric rotation, spins"});
  add_sd(out.fits, "rot_sd_per_sqrt_rad", e.rot_var_per_rad, rot.relative ? 0.0 : rot.variance_se,
         rot.relative ? 0 : nr, "rad/sqrt(rad)", rot.relative ? unused : rot.form_note);
  add_sd(out.fits, "rot_rel_sd", e.rot_rel_var, rot.relative ? rot.variance_se : 0.0, rot.relative ? nr : 0, "",
         rot.relative ? rot.form_note : unused);
  out.fits.push_back({"drift_deg_per_m", drift * kRadToDeg, heading.scale_se * kRadToDeg,
                      heading.residual_rms * kRadToDeg, "deg/m", "deg", ns,
                      "true heading change per odometric metre, straight runs"});
  add_sd(out.fits, "heading_sd_per_sqrt_m", heading_var, heading.variance_se, ns, "rad/sqrt(m)",
         "heading spread of the straight runs, less their rotation error");
  return out;
}

}  // namespace p3at::verifier::calibration_detail
