#pragma once
// The pieces of calibrate(), private to the library: what one manoeuvre
// measured, and the fits of the motion error, the kinematics and the delays.

#include <cstddef>
#include <string>
#include <vector>

#include "p3at/verifier/calibration.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::calibration_detail {

/// One interval between two consecutive rows of a manoeuvre, by odometry.
struct Interval {
  double dt_s = 0.0;
  double t_mid_s = 0.0;
  double ds_m = 0.0;          ///< along the interval's mid heading
  double dtheta_rad = 0.0;
  double cmd_trans_mps = 0.0; ///< the command in force (sent after the interval's first row)
  double cmd_rot_radps = 0.0;
};
std::vector<Interval> intervals(const Manoeuvre& m);

/// A manoeuvre's totals: odometric sums, and what the true poses at its two
/// ends say (when both are known).
struct Measure {
  const Manoeuvre* manoeuvre = nullptr;
  std::size_t cycles = 0;
  double odo_dist_m = 0.0;       ///< sum of ds (signed)
  double odo_abs_dist_m = 0.0;   ///< sum of |ds|
  double odo_dist_sq = 0.0;      ///< sum of ds^2, m^2
  double odo_rot_rad = 0.0;
  double odo_abs_rot_rad = 0.0;
  double odo_rot_sq = 0.0;
  bool has_truth = false;
  double true_rot_rad = 0.0;     ///< the true heading change, unwrapped next to odo_rot_rad
  double true_dist_m = 0.0;      ///< signed path length (the chord, corrected for constant curvature)
  double true_start_theta_rad = 0.0;  ///< the true heading at the start
  double true_dx_m = 0.0;        ///< the true displacement, world frame
  double true_dy_m = 0.0;
  /// With a true pose on every row: each cycle's odometric and true increment
  /// along the manoeuvre's axis (ds for a straight, dtheta for a spin).
  bool truth_every_row = false;
  std::vector<double> cycle_odo;
  std::vector<double> cycle_true;
};
Measure measure(const Manoeuvre& m);

/// A scale and a variance fitted together: y = scale * x + e with
/// var(e) = unit_var * L + rel_var * Q (L = sum|increment|, Q = sum
/// increment^2 over the manoeuvre; see docs/calibration.md). With a true pose
/// on every row both terms are fitted jointly; otherwise one of the two forms
/// is chosen and the other is 0.
struct ScaleFit {
  double scale = 1.0;
  double scale_se = 0.0;
  double unit_var = 0.0;      ///< per-unit term: variance per |increment|
  double unit_var_se = 0.0;
  double rel_var = 0.0;       ///< relative term: variance per increment^2
  double rel_var_se = 0.0;
  double residual_rms = 0.0;  ///< of y - scale * x
  std::size_t unit_runs = 0;  ///< manoeuvres each term was fitted from (0: not fitted, held at 0)
  std::size_t rel_runs = 0;
  std::string unit_note;      ///< how each term came about
  std::string rel_note;
  /// The variance the fit gives a manoeuvre of these sums.
  double variance(double length, double length_sq) const { return unit_var * length + rel_var * length_sq; }
};
/// Increments of single cycles, odometric and true, manoeuvre by manoeuvre,
/// when every row has a true pose.
struct CycleSeries {
  std::vector<double> odo;
  std::vector<double> truth;
};
using CycleIncrements = std::vector<CycleSeries>;
/// `per_cycle`: Q is known (rows every cycle). `allow_relative`: the model has
/// a relative term for it. `cycles`: when not empty, both terms are fitted
/// jointly, their proportions on the single cycles (far more observations).
ScaleFit fit_scale(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& length,
                   const std::vector<double>& length_sq, bool per_cycle, bool allow_relative,
                   const CycleIncrements& cycles = {});

struct MotionFit {
  MotionError motion;
  std::vector<ParameterFit> fits;
};
/// Straight runs and spins with true poses (at least 2 of each).
MotionFit fit_motion(const std::vector<Measure>& straights, const std::vector<Measure>& spins);

struct KinematicsFit {
  Kinematics kinematics;
  std::vector<ParameterFit> fits;
  std::vector<std::string> warnings;
};
/// From the odometric velocity ramps of every manoeuvre of one robot.
KinematicsFit fit_kinematics(const std::string& robot, const std::vector<const Manoeuvre*>& manoeuvres,
                             const Kinematics& defaults);

}  // namespace p3at::verifier::calibration_detail
