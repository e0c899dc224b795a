// What one manoeuvre measured: the odometric increments cycle by cycle, and
// the true motion between its two ends. Only the ends' true poses are used,
// so a tape measure at the start and the end of each run is enough.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "calibration/fit_parts.hpp"

namespace p3at::verifier::calibration_detail {
namespace {

// The angle in [-pi, pi] that differs from `a` by whole turns.
double wrap(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

}  // namespace

std::vector<Interval> intervals(const Manoeuvre& m) {
  std::vector<Interval> out;
  for (std::size_t i = 1; i < m.rows.size(); ++i) {
    const CycleRow& a = m.rows[i - 1];
    const CycleRow& b = m.rows[i];
    Interval in;
    in.dt_s = b.t_s - a.t_s;
    in.t_mid_s = (a.t_s + b.t_s) / 2.0;
    // Odometric headings may be wrapped by the robot: the increment is the short way round.
    in.dtheta_rad = wrap(b.odom_theta_rad - a.odom_theta_rad);
    const double mid = a.odom_theta_rad + in.dtheta_rad / 2.0;
    in.ds_m = (b.odom_x_m - a.odom_x_m) * std::cos(mid) + (b.odom_y_m - a.odom_y_m) * std::sin(mid);
    in.cmd_trans_mps = a.cmd_trans_mps;
    in.cmd_rot_radps = a.cmd_rot_radps;
    out.push_back(in);
  }
  return out;
}

Measure measure(const Manoeuvre& m) {
  Measure out;
  out.manoeuvre = &m;
  for (const Interval& in : intervals(m)) {
    ++out.cycles;
    out.odo_dist_m += in.ds_m;
    out.odo_abs_dist_m += std::abs(in.ds_m);
    out.odo_dist_sq += in.ds_m * in.ds_m;
    out.odo_rot_rad += in.dtheta_rad;
    out.odo_abs_rot_rad += std::abs(in.dtheta_rad);
    out.odo_rot_sq += in.dtheta_rad * in.dtheta_rad;
  }
  if (m.rows.empty() || !m.rows.front().truth || !m.rows.back().truth) return out;
  const TruePose& s = *m.rows.front().truth;
  const TruePose& e = *m.rows.back().truth;
  out.has_truth = true;
  // The true turn is within half a turn of the odometric one (any robot
  // worth calibrating errs by far less), which resolves the wrap.
  out.true_rot_rad = out.odo_rot_rad + wrap(e.theta_rad - s.theta_rad - out.odo_rot_rad);
  const double dx = e.x_m - s.x_m;
  const double dy = e.y_m - s.y_m;
  out.true_start_theta_rad = s.theta_rad;
  out.true_dx_m = dx;
  out.true_dy_m = dy;
  const double along = dx * std::cos(s.theta_rad) + dy * std::sin(s.theta_rad);
  const double chord = std::hypot(dx, dy);
  // A constant drift bends the path into an arc of angle phi: the path is
  // longer than its chord by (phi/2) / sin(phi/2).
  const double half = out.true_rot_rad / 2.0;
  const double arc = std::abs(half) > 1e-9 && std::abs(half) < 1.5 ? chord * half / std::sin(half) : chord;
  out.true_dist_m = along < 0.0 ? -arc : arc;

  // With a true pose on every row (motion capture, a simulator), each cycle
  // is an observation too: its odometric and true increment along the
  // manoeuvre's own axis (distance for a straight, rotation for a spin).
  const bool every_row = std::all_of(m.rows.begin(), m.rows.end(), [](const CycleRow& r) { return r.truth.has_value(); });
  if (!every_row) return out;
  out.truth_every_row = true;
  const std::vector<Interval> ivs = intervals(m);
  for (std::size_t i = 0; i < ivs.size(); ++i) {
    const TruePose& a = *m.rows[i].truth;
    const TruePose& b = *m.rows[i + 1].truth;
    const double dth = wrap(b.theta_rad - a.theta_rad);
    if (m.kind == ManoeuvreKind::spin) {
      out.cycle_odo.push_back(ivs[i].dtheta_rad);
      out.cycle_true.push_back(dth);
    } else {
      const double mid = a.theta_rad + dth / 2.0;
      out.cycle_odo.push_back(ivs[i].ds_m);
      out.cycle_true.push_back((b.x_m - a.x_m) * std::cos(mid) + (b.y_m - a.y_m) * std::sin(mid));
    }
  }
  return out;
}

}  // namespace p3at::verifier::calibration_detail
