#pragma once
/// How far `vipars verify` is from `vipars validate` on one mission
/// (docs/crosscheck.md, "What the scores mean"):
///
/// - strict error at a point x (a Tmax, an Rmax, or a (Tmax, Rmax) cell):
///   |v(x) - w(x)|, v the verifier's probability, w the validation's;
/// - shift-tolerant error (Lévy-type, relative shift h = 1 % of the criterion
///   value): the distance from v(x) to the interval [w(x(1-h)), w(x(1+h))],
///   0 when v(x) lies inside it. w is non-decreasing in Tmax and in Rmax, so
///   this is the smallest e with w(x(1-h)) - e <= v(x) <= w(x(1+h)) + e: the
///   band of the Lévy distance with a relative shift. On the joint surface
///   both coordinates shift together: [w(T(1-h), R(1-h)), w(T(1+h), R(1+h))].
///   The verifier's curve is not shifted (its value at x is what the gate uses);
/// - an over-confident GO cell: v >= 0.8 while the validation's whole 95 %
///   Wilson interval lies below 0.78 (ci_high < 0.78): the gate would say GO
///   at a threshold the runs say is clearly not met.
/// Each error is the maximum over the curve or the surface.

#include <cstddef>
#include <limits>
#include <vector>

namespace p3at::crosscheck {

inline constexpr double kShiftFraction = 0.01;       ///< h: 1 % of the criterion value
inline constexpr double kGoVerifyAtLeast = 0.8;       ///< a GO the verifier gives ...
inline constexpr double kGoValidationBelow = 0.78;    ///< ... that the runs' whole interval refutes

/// The accuracy bounds of issue #5: time curve, radius curve, joint surface.
struct Bounds {
  double time = 0.05;
  double radius = 0.05;
  double joint = 0.08;
};

/// The validation at one point: its probability and 95 % Wilson interval, and
/// its probability at the point shifted down and up by h.
struct ValidationPoint {
  double p = 0.0;
  double ci_low = 0.0;
  double ci_high = 1.0;
  double p_shift_low = 0.0;   ///< w(x (1 - h))
  double p_shift_high = 0.0;  ///< w(x (1 + h))
};

/// Distance from v to [p_shift_low, p_shift_high] (0 inside; the interval's
/// ends are sorted first, so a non-monotone input cannot make it negative).
double tolerant_error(double verify, const ValidationPoint& w);
/// True when v >= 0.8 and the validation's interval lies wholly below 0.78.
bool overconfident_go(double verify, const ValidationPoint& w);

/// The largest errors over a curve or a surface, and where they are.
struct ErrorSummary {
  double strict = 0.0;                 ///< max |v - w|
  double tolerant = 0.0;               ///< max shift-tolerant error
  double strict_at_tmax_s = std::numeric_limits<double>::quiet_NaN();
  double strict_at_rmax_m = std::numeric_limits<double>::quiet_NaN();
  double strict_verify = 0.0, strict_validate = 0.0;    ///< the two values where strict is largest
  double tolerant_at_tmax_s = std::numeric_limits<double>::quiet_NaN();
  double tolerant_at_rmax_m = std::numeric_limits<double>::quiet_NaN();
  double tolerant_verify = 0.0, tolerant_validate = 0.0;
  std::size_t points = 0;
};

/// A cell where the gate would wrongly say GO.
struct OverconfidentCell {
  double tmax_s = 0.0, rmax_m = 0.0;
  double verify = 0.0, validate = 0.0, ci_low = 0.0, ci_high = 0.0;
};

struct MissionScore {
  ErrorSummary time;       ///< P(t <= Tmax) over the Tmax axis
  ErrorSummary radius;     ///< P(every r <= Rmax) over the Rmax axis
  ErrorSummary joint;      ///< the joint surface
  std::size_t overconfident_go_cells = 0;       ///< on the joint surface
  std::vector<OverconfidentCell> overconfident; ///< up to the 5 with the largest v - w, largest first
  /// All three errors within their bounds (strict or shift-tolerant).
  bool within(const Bounds& b, bool tolerant) const;
};

/// One curve: verify values, and the validation at each axis value. Axis
/// values are Tmax (s) for the time curve, Rmax (m) for the radius curve.
/// Throws std::invalid_argument when the lengths differ.
ErrorSummary score_curve(const std::vector<double>& axis, const std::vector<double>& verify,
                         const std::vector<ValidationPoint>& validation, bool is_time_axis);

/// The whole mission: both curves and the joint surface ([tmax][rmax]).
/// Over-confident GO cells are counted on `decided_joint` when given: at each
/// cell the probability the gate decides on there (verifier::decision_point(),
/// 1 % stricter, and more for a curve-shifting approximation), since that is
/// what it says GO on; the errors are always the raw surface's.
/// Throws std::invalid_argument when shapes differ.
MissionScore score_mission(const std::vector<double>& tmax, const std::vector<double>& rmax,
                           const std::vector<double>& verify_time, const std::vector<double>& verify_radius,
                           const std::vector<std::vector<double>>& verify_joint,
                           const std::vector<ValidationPoint>& validation_time,
                           const std::vector<ValidationPoint>& validation_radius,
                           const std::vector<std::vector<ValidationPoint>>& validation_joint,
                           const std::vector<std::vector<double>>* decided_joint = nullptr);

}  // namespace p3at::crosscheck
