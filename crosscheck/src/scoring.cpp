// The cross-check scores (scoring.hpp, docs/crosscheck.md).

#include "p3at/crosscheck/scoring.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace p3at::crosscheck {

double tolerant_error(double verify, const ValidationPoint& w) {
  const double lo = std::min(w.p_shift_low, w.p_shift_high);
  const double hi = std::max(w.p_shift_low, w.p_shift_high);
  if (verify < lo) return lo - verify;
  if (verify > hi) return verify - hi;
  return 0.0;
}

bool overconfident_go(double verify, const ValidationPoint& w) {
  return verify >= kGoVerifyAtLeast && w.ci_high < kGoValidationBelow;
}

bool MissionScore::within(const Bounds& b, bool tolerant) const {
  const auto e = [tolerant](const ErrorSummary& s) { return tolerant ? s.tolerant : s.strict; };
  return e(time) <= b.time && e(radius) <= b.radius && e(joint) <= b.joint;
}

namespace {

// Folds one point into a summary; the first point of the largest error is kept.
void add_point(ErrorSummary& s, double tmax_s, double rmax_m, double v, const ValidationPoint& w) {
  ++s.points;
  const double strict = std::abs(v - w.p);
  if (s.points == 1 || strict > s.strict) {
    s.strict = strict;
    s.strict_at_tmax_s = tmax_s;
    s.strict_at_rmax_m = rmax_m;
    s.strict_verify = v;
    s.strict_validate = w.p;
  }
  const double tol = tolerant_error(v, w);
  if (s.points == 1 || tol > s.tolerant) {
    s.tolerant = tol;
    s.tolerant_at_tmax_s = tmax_s;
    s.tolerant_at_rmax_m = rmax_m;
    s.tolerant_verify = v;
    s.tolerant_validate = w.p;
  }
}

}  // namespace

ErrorSummary score_curve(const std::vector<double>& axis, const std::vector<double>& verify,
                         const std::vector<ValidationPoint>& validation, bool is_time_axis) {
  if (axis.size() != verify.size() || axis.size() != validation.size()) {
    throw std::invalid_argument("score_curve: axis, verify and validation differ in length");
  }
  ErrorSummary s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < axis.size(); ++i) {
    add_point(s, is_time_axis ? axis[i] : nan, is_time_axis ? nan : axis[i], verify[i], validation[i]);
  }
  return s;
}

MissionScore score_mission(const std::vector<double>& tmax, const std::vector<double>& rmax,
                           const std::vector<double>& verify_time, const std::vector<double>& verify_radius,
                           const std::vector<std::vector<double>>& verify_joint,
                           const std::vector<ValidationPoint>& validation_time,
                           const std::vector<ValidationPoint>& validation_radius,
                           const std::vector<std::vector<ValidationPoint>>& validation_joint,
                           const std::vector<std::vector<double>>* decided_joint) {
  MissionScore m;
  m.time = score_curve(tmax, verify_time, validation_time, true);
  m.radius = score_curve(rmax, verify_radius, validation_radius, false);
  if (verify_joint.size() != tmax.size() || validation_joint.size() != tmax.size()) {
    throw std::invalid_argument("score_mission: the joint surface needs one row per Tmax");
  }
  for (std::size_t i = 0; i < tmax.size(); ++i) {
    if (verify_joint[i].size() != rmax.size() || validation_joint[i].size() != rmax.size()) {
      throw std::invalid_argument("score_mission: each joint row needs one value per Rmax");
    }
    for (std::size_t j = 0; j < rmax.size(); ++j) {
      const double v = verify_joint[i][j];
      const ValidationPoint& w = validation_joint[i][j];
      add_point(m.joint, tmax[i], rmax[j], v, w);
      const double decided = decided_joint != nullptr ? decided_joint->at(i).at(j) : v;
      if (overconfident_go(decided, w)) {
        ++m.overconfident_go_cells;
        m.overconfident.push_back({tmax[i], rmax[j], decided, w.p, w.ci_low, w.ci_high});
      }
    }
  }
  std::stable_sort(m.overconfident.begin(), m.overconfident.end(), [](const OverconfidentCell& a, const OverconfidentCell& b) {
    return a.verify - a.validate > b.verify - b.validate;
  });
  if (m.overconfident.size() > 5) m.overconfident.resize(5);
  return m;
}

}  // namespace p3at::crosscheck
