// Where within its last cycle a trigger fires (engine/trigger_phase.hpp):
// the expected gap between the threshold crossing and the check that fires,
// and the gap's variance, against a direct numerical integration over the
// crossing time's normal distribution.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

#include "engine/trigger_phase.hpp"

namespace {

struct Moments {
  double mean = 0.0, var = 0.0;
};

/// E and Var of ceil(X) - X for X ~ N(t, sd^2), by the midpoint rule over
/// t +- 8 sd in steps far finer than a cycle.
Moments integrated(double t, double sd) {
  const double kPi = 3.14159265358979323846;
  const int n = 400000;
  const double lo = t - 8.0 * sd, h = 16.0 * sd / n;
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = lo + (i + 0.5) * h;
    const double z = (x - t) / sd;
    const double w = std::exp(-0.5 * z * z) / (sd * std::sqrt(2.0 * kPi)) * h;
    double gap = std::ceil(x) - x;
    if (gap <= 0.0) gap = 1.0;
    m0 += w;
    m1 += w * gap;
    m2 += w * gap * gap;
  }
  Moments m;
  m.mean = m1 / m0;
  m.var = m2 / m0 - m.mean * m.mean;
  return m;
}

}  // namespace

using p3at::verifier::engine::check_gap_variance;
using p3at::verifier::engine::expected_check_gap;

TEST_CASE("one deterministic crossing fires at one check: no spread of where along the step") {
  CHECK(check_gap_variance(3.3, 0.0) == 0.0);
  CHECK(expected_check_gap(3.3, 0.0) == doctest::Approx(0.7));
}

TEST_CASE("a crossing that varies by cycles fires anywhere in the cycle after it: the uniform gap's 1/12") {
  CHECK(check_gap_variance(3.3, 5.0) == doctest::Approx(1.0 / 12.0));
  CHECK(check_gap_variance(3.3, 2.0) == doctest::Approx(1.0 / 12.0).epsilon(1e-3));
  CHECK(expected_check_gap(3.3, 2.0) == doctest::Approx(0.5).epsilon(1e-3));
}

TEST_CASE("in between, the gap's mean and variance are the integrals over the crossing time") {
  // A crossing just before a check fires there or, a little later, a whole
  // cycle after: more spread than a uniform gap.
  CHECK(check_gap_variance(0.93, 0.1) > 1.0 / 12.0);
  for (const double t : {0.1, 0.5, 0.93, 7.25}) {
    for (const double sd : {0.02, 0.1, 0.25, 0.6}) {
      const Moments m = integrated(t, sd);
      INFO("t " << t << " sd " << sd);
      CHECK(expected_check_gap(t, sd) == doctest::Approx(m.mean).epsilon(1e-4));
      CHECK(check_gap_variance(t, sd) == doctest::Approx(m.var).epsilon(2e-3));
      CHECK(check_gap_variance(t, sd) <= 0.25);
    }
  }
}

TEST_CASE("the checks a crossing fires at: the normal's mass in each cycle before a check") {
  using p3at::verifier::engine::check_shares;
  SUBCASE("no spread: the one check at or after the crossing") {
    const auto one = check_shares(14.88, 0.0);
    REQUIRE(one.size() == 1);
    CHECK(one.front().check == 15);
    CHECK(one.front().share == 1.0);
    CHECK(check_shares(15.0, 0.0).front().check == 15);  // on a check: fires there
  }
  SUBCASE("a crossing 0.12 cycle before check 15 with sd 0.1: check 16 takes Phi(-1.2)") {
    const auto split = check_shares(14.88, 0.1);
    double total = 0.0, at16 = 0.0;
    for (const auto& c : split) {
      total += c.share;
      if (c.check == 16) at16 = c.share;
      CHECK(c.check >= 14);
      CHECK(c.check <= 17);
    }
    CHECK(total == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(at16 == doctest::Approx(0.11507).epsilon(1e-3));
  }
  SUBCASE("never a check before the first cycle") {
    for (const auto& c : check_shares(0.2, 0.5)) CHECK(c.check >= 1);
  }
}
