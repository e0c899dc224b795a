// The cross-check scores on hand-made curves, surfaces and intervals, whose
// answers follow from the definitions in scoring.hpp / docs/crosscheck.md.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "p3at/crosscheck/grid_choice.hpp"
#include "p3at/crosscheck/scoring.hpp"

using namespace p3at::crosscheck;

namespace {

// A steep empirical step: 0 below `at`, 1 from `at` on.
double step(double x, double at) { return x >= at ? 1.0 : 0.0; }

// The validation of a step at `at` on an axis, with its shifted values.
std::vector<ValidationPoint> step_validation(const std::vector<double>& axis, double at) {
  std::vector<ValidationPoint> out;
  for (double x : axis) {
    const double p = step(x, at);
    out.push_back({p, std::max(0.0, p - 0.01), std::min(1.0, p + 0.01), step(x * (1 - kShiftFraction), at),
                   step(x * (1 + kShiftFraction), at)});
  }
  return out;
}

}  // namespace

TEST_CASE("tolerant error: the distance to the shifted band, 0 inside it") {
  const ValidationPoint w{0.5, 0.45, 0.55, 0.3, 0.7};
  CHECK(tolerant_error(0.5, w) == 0.0);
  CHECK(tolerant_error(0.3, w) == 0.0);
  CHECK(tolerant_error(0.7, w) == 0.0);
  CHECK(tolerant_error(0.1, w) == doctest::Approx(0.2));
  CHECK(tolerant_error(0.95, w) == doctest::Approx(0.25));
  // Ends given the wrong way round are sorted, never a negative error.
  const ValidationPoint swapped{0.5, 0.45, 0.55, 0.7, 0.3};
  CHECK(tolerant_error(0.5, swapped) == 0.0);
  CHECK(tolerant_error(0.8, swapped) == doctest::Approx(0.1));
}

TEST_CASE("a curve offset by less than 1 % fails strictly and passes with the shift") {
  // Tmax axis 99.0 .. 101.0 s in steps of 0.1; validation steps at 100.0 s,
  // the verifier at 100.5 s (0.5 % later): at 100.0 .. 100.4 s they differ by 1.
  std::vector<double> axis, v;
  for (int k = 0; k <= 20; ++k) axis.push_back(99.0 + 0.1 * k);
  for (double x : axis) v.push_back(step(x, 100.5 - 1e-9));
  const ErrorSummary s = score_curve(axis, v, step_validation(axis, 100.0 - 1e-9), true);
  CHECK(s.strict == 1.0);
  CHECK(s.strict_at_tmax_s == doctest::Approx(100.0));
  CHECK(std::isnan(s.strict_at_rmax_m));
  CHECK(s.strict_verify == 0.0);
  CHECK(s.strict_validate == 1.0);
  CHECK(s.tolerant == 0.0);
  CHECK(s.points == 21);

  // 2 % later: outside the 1 % band too (from 101.1 s on, where w(x (1 - h)) is already 1).
  std::vector<double> wide, late;
  for (int k = 0; k <= 50; ++k) wide.push_back(99.0 + 0.1 * k);
  for (double x : wide) late.push_back(step(x, 102.0));
  const ErrorSummary t = score_curve(wide, late, step_validation(wide, 100.0 - 1e-9), true);
  CHECK(t.strict == 1.0);
  CHECK(t.tolerant == 1.0);
}

TEST_CASE("a smooth curve: strict and tolerant errors by hand") {
  // Validation w(x) = x / 10 on 1..9 (so w(x(1±h)) = x(1±h)/10); verify = w + 0.03.
  std::vector<double> axis, v;
  std::vector<ValidationPoint> w;
  for (int k = 1; k <= 9; ++k) {
    const double x = k;
    axis.push_back(x);
    v.push_back(x / 10 + 0.03);
    w.push_back({x / 10, x / 10 - 0.02, x / 10 + 0.02, x * 0.99 / 10, x * 1.01 / 10});
  }
  const ErrorSummary s = score_curve(axis, v, w, false);
  CHECK(s.strict == doctest::Approx(0.03));
  // Tolerant: v - w(x(1+h)) = 0.03 - x/1000, largest at x = 1: 0.029.
  CHECK(s.tolerant == doctest::Approx(0.029));
  CHECK(s.tolerant_at_rmax_m == doctest::Approx(1.0));
  CHECK(std::isnan(s.tolerant_at_tmax_s));
  CHECK_THROWS_AS(score_curve(axis, {0.1}, w, false), std::invalid_argument);
}

TEST_CASE("over-confident GO: verify >= 0.8 while the whole interval lies below 0.78") {
  const auto w = [](double lo, double hi) { return ValidationPoint{(lo + hi) / 2, lo, hi, 0, 1}; };
  CHECK(overconfident_go(0.8, w(0.70, 0.779)));
  CHECK(overconfident_go(1.0, w(0.40, 0.52)));
  CHECK_FALSE(overconfident_go(0.799, w(0.40, 0.52)));   // not a GO
  CHECK_FALSE(overconfident_go(0.9, w(0.70, 0.78)));     // the interval reaches 0.78
  CHECK_FALSE(overconfident_go(0.9, w(0.75, 0.85)));
}

TEST_CASE("score_mission: the joint surface's errors and over-confident cells") {
  const std::vector<double> tmax{10, 20}, rmax{1, 2, 3};
  const std::vector<double> vt{0.5, 0.9}, vr{0.6, 0.9, 1.0};
  const std::vector<std::vector<double>> vj{{0.2, 0.4, 0.5}, {0.5, 0.85, 0.95}};
  const auto pt = [](double p, double lo, double hi) { return ValidationPoint{p, lo, hi, p, p}; };
  const std::vector<ValidationPoint> wt{pt(0.5, 0.4, 0.6), pt(0.9, 0.85, 0.95)};
  const std::vector<ValidationPoint> wr{pt(0.6, 0.5, 0.7), pt(0.9, 0.85, 0.95), pt(1, 0.99, 1)};
  const std::vector<std::vector<ValidationPoint>> wj{
      {pt(0.2, 0.1, 0.3), pt(0.4, 0.3, 0.5), pt(0.5, 0.4, 0.6)},
      {pt(0.5, 0.4, 0.6), pt(0.70, 0.66, 0.74), pt(0.6, 0.55, 0.65)}};
  const MissionScore m = score_mission(tmax, rmax, vt, vr, vj, wt, wr, wj);
  CHECK(m.time.strict == 0.0);
  CHECK(m.radius.strict == 0.0);
  CHECK(m.joint.strict == doctest::Approx(0.35));   // 0.95 vs 0.6 at (20 s, 3 m)
  CHECK(m.joint.strict_at_tmax_s == 20);
  CHECK(m.joint.strict_at_rmax_m == 3);
  CHECK(m.joint.points == 6);
  REQUIRE(m.overconfident_go_cells == 2);           // (20, 2) and (20, 3)
  REQUIRE(m.overconfident.size() == 2);
  CHECK(m.overconfident[0].rmax_m == 3);            // the larger v - w first
  CHECK(m.overconfident[1].verify == doctest::Approx(0.85));
  Bounds b;
  CHECK_FALSE(m.within(b, false));
  CHECK_FALSE(m.within(b, true));
  b.joint = 0.4;
  CHECK(m.within(b, false));
  CHECK_THROWS_AS(score_mission(tmax, rmax, vt, vr, {{0.1}}, wt, wr, wj), std::invalid_argument);
}

TEST_CASE("grid choice: round steps covering where a curve rises") {
  const Axis a = nice_axis(187.3, 203.9, 41, 0.1);
  CHECK(a.values.size() <= 41);
  CHECK(a.values.size() >= 15);
  CHECK(a.values.front() <= 187.3);
  CHECK(a.values.back() >= 203.9);
  CHECK(a.step == 0.5);
  CHECK(a.range() == "186.5:205:0.5");  // padded by 4 % of the span: 186.6 .. 204.6
  // Rmax never at or below 0.
  const Axis r = nice_axis(0.0, 0.4, 31, 0.01);
  CHECK(r.values.front() > 0.0);
  // A curve: flat 0, rising between 3 and 6, flat 1.
  const std::vector<double> x{1, 2, 3, 4, 5, 6, 7, 8};
  const Rise rise = rise_of_curve(x, {0, 0, 0, 0.3, 0.7, 1, 1, 1});
  CHECK(rise.found);
  CHECK(rise.lo == 3);
  CHECK(rise.hi == 6);
  CHECK_FALSE(rise_of_curve(x, {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5}).found);
  const Rise sample = rise_of_sample({5, 1, 3, std::numeric_limits<double>::infinity(), 2, 4});
  CHECK(sample.found);
  CHECK(sample.lo == 1);
  CHECK(sample.hi == 5);
  CHECK_FALSE(rise_of_sample({std::numeric_limits<double>::infinity()}).found);
  CHECK(round15(0.1 + 0.2) == 0.3);
}
