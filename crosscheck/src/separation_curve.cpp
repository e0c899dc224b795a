// The closest-approach curve (separation_curve.hpp).

#include "p3at/crosscheck/separation_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "p3at/crosscheck/grid_choice.hpp"
#include "p3at/team_sim/wilson.hpp"
#include "p3at/verifier/separation.hpp"

namespace p3at::crosscheck {

std::optional<SeparationScore> score_separation(const verifier::SystemOutcome& outcome,
                                                const std::vector<team_sim::RunResult>& runs, std::size_t points,
                                                double step_m) {
  std::vector<double> closest;
  for (const team_sim::RunResult& r : runs) {
    if (r.robots.size() >= 2 && std::isfinite(r.closest_approach_m)) closest.push_back(r.closest_approach_m);
  }
  if (closest.empty()) return std::nullopt;
  std::sort(closest.begin(), closest.end());
  // From a little below the runs' closest to a little above where 99.5 % of
  // them stay apart, but not beyond what the verifier can vouch for.
  const double reach = 0.5 * verifier::kSeparationHorizonM;
  const double q_hi = closest[static_cast<std::size_t>(0.995 * static_cast<double>(closest.size() - 1))];
  const double lo = std::max(0.05, closest.front() - 0.25);
  const double hi = std::min(reach, q_hi + 0.25);
  if (!(hi - lo >= 0.05)) return std::nullopt;
  Axis axis = nice_axis(lo, hi, points, 0.01);
  axis.values.erase(std::remove_if(axis.values.begin(), axis.values.end(), [&](double d) { return d > reach; }),
                    axis.values.end());
  if (axis.values.empty()) return std::nullopt;
  axis.last = axis.values.back();

  const auto measured = [&](double d) {
    const auto apart = static_cast<std::uint64_t>(closest.end() - std::upper_bound(closest.begin(), closest.end(), d));
    return apart;
  };
  const std::uint64_t n = closest.size();
  std::vector<double> verify;
  std::vector<ValidationPoint> validation;
  // Every d and the distance it is decided at, asked in one pass (the
  // branches' pairs are cut into stretches once, not once per d).
  std::vector<double> asked = axis.values;
  for (const double d : axis.values) asked.push_back(verifier::decided_separation(d, true, step_m));
  const std::vector<double> answers = verifier::probability_no_pair_within(outcome, asked);
  SeparationScore s;
  for (std::size_t a = 0; a < axis.values.size(); ++a) {
    const double d = axis.values[a];
    const double v = answers[a];
    const std::uint64_t k = measured(d);
    const team_sim::Interval ci = team_sim::wilson_interval(k, n);
    ValidationPoint w;
    w.p = static_cast<double>(k) / static_cast<double>(n);
    w.ci_low = ci.low;
    w.ci_high = ci.high;
    w.p_shift_low = static_cast<double>(measured(d * (1.0 - kShiftFraction))) / static_cast<double>(n);
    w.p_shift_high = static_cast<double>(measured(d * (1.0 + kShiftFraction))) / static_cast<double>(n);
    const double decided = answers[axis.values.size() + a];
    s.overconfident_points += overconfident_go(decided, w);
    verify.push_back(v);
    validation.push_back(w);
  }
  s.range = axis.range();
  s.error = score_curve(axis.values, verify, validation, false);
  return s;
}

}  // namespace p3at::crosscheck
