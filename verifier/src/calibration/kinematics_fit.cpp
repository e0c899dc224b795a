// The base's kinematics (models.hpp: Kinematics) from the odometry of each
// cycle: the accelerations are the rates of the ramps after a manoeuvre's
// command starts and after it returns to zero (ramp_fit.hpp: fitted on the
// travel, started from the slope of the speeds), the rotational cap the
// plateau of spins commanded faster than the robot turns, the cycle the
// median time between rows. The ramps need no ground truth.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "calibration/fit_parts.hpp"
#include "calibration/ramp_fit.hpp"

namespace p3at::verifier::calibration_detail {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// Only the middle of a ramp is linear in the per-cycle averages: the cycle in
// which it starts and the one in which it reaches the plateau average a
// partial ramp. Keeping speeds between these shares of the plateau leaves
// both out.
constexpr double kRampLow = 0.2;
constexpr double kRampHigh = 0.8;
// A spin is limited by the cap when commanded this much faster than it turned.
constexpr double kSaturated = 1.05;
// Rows a manoeuvre needs to count as logged every cycle, and cycles at the
// top that make a plateau.
constexpr std::size_t kMinRows = 4;
constexpr std::size_t kMinPlateauCycles = 3;
// Rows of plateau (and of rest after a slow-down) a ramp's trace carries
// besides the ramp: they pin its offset and its end. A speed below this share
// of the plateau counts as at rest.
constexpr std::size_t kTraceTopRows = 3;
constexpr std::size_t kTraceRestRows = 3;
constexpr double kAtRest = 0.05;

struct Ramp {
  std::vector<double> t;
  std::vector<double> v;  ///< |velocity|
};

/// A manoeuvre kind's ramps of one direction (speed-ups or slow-downs).
struct RampSet {
  std::vector<Ramp> speeds;       ///< the 20-80 % speeds, for the first estimate
  std::vector<RampTrace> traces;  ///< the travel, for the fit
};

struct Plateau {
  double speed = 0.0;    ///< mean |velocity| at the top
  double command = 0.0;  ///< |command|
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

// The rows [first, last] of a manoeuvre as a ramp's trace: the travel along
// the command's direction (`sign`), from the increments of `ivs`.
RampTrace trace_of(const std::vector<Interval>& ivs, const Manoeuvre& m, std::size_t first, std::size_t last,
                   double sign, bool rotation) {
  RampTrace tr;
  double travel = 0.0;
  for (std::size_t row = first; row <= last; ++row) {
    if (row > first) travel += sign * (rotation ? ivs[row - 1].dtheta_rad : ivs[row - 1].ds_m);
    tr.t_s.push_back(m.rows[row].t_s);
    tr.travel.push_back(travel);
  }
  return tr;
}

// The speed-up after the command starts, the slow-down after it returns to 0:
// their 20-80 % speeds (for a first estimate) and their travel (for the fit).
void collect(const Manoeuvre& m, RampSet& up_set, RampSet& down_set, std::vector<Plateau>& plateaus) {
  const bool rotation = m.kind == ManoeuvreKind::spin;
  const std::vector<Interval> ivs = intervals(m);
  std::vector<double> speed;
  std::vector<double> command;
  for (const Interval& in : ivs) {
    if (!(in.dt_s > 0.0)) return;
    speed.push_back(std::abs(rotation ? in.dtheta_rad : in.ds_m) / in.dt_s);
    command.push_back(rotation ? in.cmd_rot_radps : in.cmd_trans_mps);
  }
  const std::size_t n = ivs.size();
  std::size_t a = 0;
  while (a < n && command[a] == 0.0) ++a;
  if (a == n) return;
  std::size_t b = a;
  while (b < n && command[b] == command[a]) ++b;
  const double sign = command[a] > 0.0 ? 1.0 : -1.0;

  // The plateau: the mean speed from the cycle after the ramp first comes
  // near the peak (that one may be partial) until the command changes. A
  // mean, not a median: odometry is quantised (1/4096 turn on a P3-AT), and
  // only an average over many cycles falls between the steps.
  const double peak = *std::max_element(speed.begin() + static_cast<std::ptrdiff_t>(a),
                                        speed.begin() + static_cast<std::ptrdiff_t>(b));
  if (!(peak > 0.0)) return;
  std::size_t r = a;
  while (speed[r] < 0.9 * peak) ++r;
  const std::size_t near_top = r;
  if (r + 1 < b) ++r;
  double sum = 0.0;
  for (std::size_t i = r; i < b; ++i) sum += speed[i];
  const double plateau = sum / static_cast<double>(b - r);
  const bool has_plateau = b - r >= kMinPlateauCycles;
  if (has_plateau) plateaus.push_back(Plateau{plateau, std::abs(command[a])});

  Ramp up;
  std::size_t first_above_low = b;
  for (std::size_t i = a; i < b && speed[i] < 0.9 * plateau; ++i) {
    if (speed[i] > kRampLow * plateau && first_above_low == b) first_above_low = i;
    if (speed[i] > kRampLow * plateau && speed[i] < kRampHigh * plateau) {
      up.t.push_back(ivs[i].t_mid_s);
      up.v.push_back(speed[i]);
    }
  }
  up_set.speeds.push_back(up);
  // The travel from the row the command starts at to a few rows into the
  // plateau; the ramp starts before the end of its first cycle above 20 %.
  if (has_plateau && first_above_low < b) {
    RampTrace tr = trace_of(ivs, m, a, std::min(near_top + 1 + kTraceTopRows, b), sign, rotation);
    tr.plateau = plateau;
    tr.start_lo_s = m.rows[a].t_s - ivs[a].dt_s;
    tr.start_hi_s = m.rows[first_above_low + 1].t_s;
    up_set.traces.push_back(std::move(tr));
  }

  Ramp down;
  std::size_t i = b;
  while (i < n && command[i] == 0.0 && speed[i] >= kRampHigh * plateau) ++i;  // the command's latency
  const std::size_t first_below_high = i;
  for (; i < n && command[i] == 0.0 && speed[i] > kRampLow * plateau; ++i) {
    if (speed[i] < kRampHigh * plateau) {
      down.t.push_back(ivs[i].t_mid_s);
      down.v.push_back(speed[i]);
    }
  }
  down_set.speeds.push_back(down);
  // From a few plateau rows before the command returns to 0 to a few rows at
  // rest (or the log's end: a manoeuvre may stop logging once at rest).
  std::size_t rest = i;
  while (rest < n && command[rest] == 0.0 && speed[rest] > kAtRest * plateau) ++rest;
  if (has_plateau && first_below_high < n) {
    const std::size_t first = b >= r + kTraceTopRows ? b - kTraceTopRows : r;
    std::size_t last = rest;
    while (last < n && last < rest + 1 + kTraceRestRows && command[last] == 0.0) ++last;
    RampTrace tr = trace_of(ivs, m, first, last, sign, rotation);
    tr.plateau = plateau;
    tr.slowing = true;
    tr.start_lo_s = m.rows[b].t_s - ivs[b].dt_s;
    tr.start_hi_s = m.rows[first_below_high + 1].t_s;
    down_set.traces.push_back(std::move(tr));
  }
}

struct SlopeFit {
  bool ok = false;
  double slope = 0.0;
  double se = 0.0;
  double rms = 0.0;
  std::size_t ramps = 0;
};

// One slope shared by every ramp, each with its own intercept (the ramps
// start at different times).
SlopeFit pooled_slope(const std::vector<Ramp>& ramps) {
  SlopeFit out;
  double sxy = 0.0;
  double sxx = 0.0;
  std::size_t points = 0;
  for (const Ramp& r : ramps) {
    if (r.t.size() < 2) continue;
    double tm = 0.0;
    double vm = 0.0;
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      tm += r.t[i];
      vm += r.v[i];
    }
    tm /= static_cast<double>(r.t.size());
    vm /= static_cast<double>(r.t.size());
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      sxy += (r.t[i] - tm) * (r.v[i] - vm);
      sxx += (r.t[i] - tm) * (r.t[i] - tm);
    }
    points += r.t.size();
    ++out.ramps;
  }
  if (out.ramps < 2 || !(sxx > 0.0)) return out;
  out.slope = sxy / sxx;
  double ssr = 0.0;
  for (const Ramp& r : ramps) {
    if (r.t.size() < 2) continue;
    double tm = 0.0;
    double vm = 0.0;
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      tm += r.t[i];
      vm += r.v[i];
    }
    tm /= static_cast<double>(r.t.size());
    vm /= static_cast<double>(r.t.size());
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      const double res = r.v[i] - vm - out.slope * (r.t[i] - tm);
      ssr += res * res;
    }
  }
  const std::size_t dof = points > out.ramps + 1 ? points - out.ramps - 1 : 1;
  out.se = std::sqrt(ssr / static_cast<double>(dof) / sxx);
  out.rms = std::sqrt(ssr / static_cast<double>(points));
  out.ok = true;
  return out;
}

// Fills `value` (SI) and its report line from a kind's ramps (`what`: which
// ones, for the note), or keeps the default: the speeds' slope starts the
// search and the travel decides; with fewer than 2 ramps that reach a plateau
// (short manoeuvres) the slope stands, and the note says so. A spin's are
// reported in degrees.
void ramp_parameter(const RampSet& ramps, double sign, bool rotation, const std::string& name, const std::string& what,
                    double& value, KinematicsFit& out, const std::string& robot) {
  const double unit_scale = rotation ? kRadToDeg : 1.0;
  const std::string travel_unit = rotation ? "deg" : "m";
  ParameterFit f;
  f.name = name;
  f.unit = travel_unit + "/s^2";
  const SlopeFit first = pooled_slope(ramps.speeds);
  const RampFit fit = first.ok ? fit_ramp_rate(ramps.traces, sign * first.slope) : RampFit{};
  if (fit.ok) {
    value = fit.rate;
    f.value = fit.rate * unit_scale;
    f.std_error = fit.se * unit_scale;
    f.residual_rms = fit.rms * unit_scale;
    f.residual_unit = travel_unit;
    f.runs = fit.ramps;
    f.note = std::string(rotation ? "odometric turn of the " : "odometric travel of the ") + what;
  } else if (first.ok && sign * first.slope > 0.0) {
    value = sign * first.slope;
    f.value = value * unit_scale;
    f.std_error = first.se * unit_scale;
    f.residual_rms = first.rms * unit_scale;
    f.residual_unit = travel_unit + "/s";
    f.runs = first.ramps;
    f.note = "slope of the 20-80 % speeds of the " + what + " (fewer than 2 reach a plateau: 1-2 % low)";
  } else {
    f.value = value * unit_scale;
    f.note = "default kept: fewer than 2 usable ramps";
    out.warnings.push_back(robot + ": " + name + " not measured (fewer than 2 usable ramps): default kept");
  }
  out.fits.push_back(f);
}

}  // namespace

KinematicsFit fit_kinematics(const std::string& robot, const std::vector<const Manoeuvre*>& manoeuvres,
                             const Kinematics& defaults) {
  KinematicsFit out;
  Kinematics& k = out.kinematics;
  k = defaults;

  std::vector<double> dts;
  RampSet trans_up, trans_down, rot_up, rot_down;
  std::vector<Plateau> trans_plateaus, rot_plateaus;
  std::size_t used = 0;
  for (const Manoeuvre* m : manoeuvres) {
    // Ramps and cycles need a row every cycle; a log with only each
    // manoeuvre's ends says nothing about them.
    if (m->rows.size() < kMinRows) continue;
    ++used;
    for (const Interval& in : intervals(*m)) dts.push_back(in.dt_s);
    if (m->kind == ManoeuvreKind::spin) {
      collect(*m, rot_up, rot_down, rot_plateaus);
    } else {
      collect(*m, trans_up, trans_down, trans_plateaus);
    }
  }

  ParameterFit cycle{"cycle_s", k.cycle_s, -1.0, -1.0, "s", "s", 0, ""};
  if (!dts.empty()) {
    // Rounded to a microsecond: timestamps in seconds carry decimal noise.
    k.cycle_s = std::max(std::round(median(dts) * 1e6) / 1e6, 1e-6);
    double sq = 0.0;
    for (double dt : dts) sq += (dt - k.cycle_s) * (dt - k.cycle_s);
    cycle.value = k.cycle_s;
    cycle.residual_rms = std::sqrt(sq / static_cast<double>(dts.size()));
    cycle.runs = used;
    cycle.note = "median time between rows (" + std::to_string(dts.size()) + " cycles)";
  } else {
    cycle.note = "default kept: no manoeuvre logged every cycle";
    out.warnings.push_back(robot + ": cycle_s not measured (no manoeuvre logged every cycle): default kept");
  }
  out.fits.push_back(cycle);

  ramp_parameter(trans_up, 1.0, false, "trans_accel_mps2", "speed-ups", k.trans_accel_mps2, out, robot);
  ramp_parameter(trans_down, -1.0, false, "trans_decel_mps2", "slow-downs", k.trans_decel_mps2, out, robot);
  ramp_parameter(rot_up, 1.0, true, "rot_accel_degps2", "spins' speed-ups", k.rot_accel_radps2, out, robot);
  ramp_parameter(rot_down, -1.0, true, "rot_decel_degps2", "spins' slow-downs", k.rot_decel_radps2, out, robot);

  std::vector<double> capped;
  double fastest = 0.0;
  for (const Plateau& p : rot_plateaus) {
    fastest = std::max(fastest, p.speed);
    if (p.command > kSaturated * p.speed) capped.push_back(p.speed);
  }
  ParameterFit cap{"max_rot_vel_degps", k.max_rot_vel_radps * kRadToDeg, -1.0, -1.0, "deg/s", "deg/s", 0, ""};
  if (!capped.empty()) {
    double sum = 0.0;
    for (double c : capped) sum += c;
    k.max_rot_vel_radps = sum / static_cast<double>(capped.size());
    double sq = 0.0;
    for (double c : capped) sq += (c - k.max_rot_vel_radps) * (c - k.max_rot_vel_radps);
    cap.value = k.max_rot_vel_radps * kRadToDeg;
    cap.residual_rms = std::sqrt(sq / static_cast<double>(capped.size())) * kRadToDeg;
    if (capped.size() > 1) cap.std_error = cap.residual_rms / std::sqrt(static_cast<double>(capped.size() - 1));
    cap.runs = capped.size();
    cap.note = "plateau of spins commanded faster";
  } else {
    cap.note = "default kept: no spin was commanded faster than the robot turned";
    out.warnings.push_back(robot + ": max_rot_vel_degps not measured (no spin commanded above the cap): default kept");
    if (fastest > k.max_rot_vel_radps) {
      out.warnings.push_back(robot + ": a spin turned at " + std::to_string(fastest * kRadToDeg) +
                             " deg/s, above the default cap");
    }
  }
  out.fits.push_back(cap);

  out.fits.push_back({"robot_radius_m", k.robot_radius_m, -1.0, -1.0, "m", "", 0, "the executive's setting, not measured"});
  out.fits.push_back({"rot_gain", k.rot_gain, -1.0, -1.0, "", "", 0, "the executive's setting, not measured"});
  return out;
}

}  // namespace p3at::verifier::calibration_detail
