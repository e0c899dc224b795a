// Wilson score intervals against published values (Newcombe, "Two-sided
// confidence intervals for the single proportion", Stat. Med. 1998, Table I,
// method 3) and the edge cases a campaign meets: 0 or n successes, no runs.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>

#include "p3at/team_sim/wilson.hpp"

using p3at::team_sim::wilson_interval;

namespace {

void check(std::uint64_t x, std::uint64_t n, double low, double high) {
  CAPTURE(x);
  CAPTURE(n);
  const auto ci = wilson_interval(x, n);
  // The published values are rounded to 4 decimals.
  CHECK(std::fabs(ci.low - low) <= 5e-5);
  CHECK(std::fabs(ci.high - high) <= 5e-5);
}

}  // namespace

TEST_CASE("Wilson interval: published values") {
  check(90, 100, 0.8256, 0.9448);
  check(81, 263, 0.2553, 0.3662);
  check(15, 148, 0.0624, 0.1605);
  check(1, 29, 0.0061, 0.1718);
}

TEST_CASE("Wilson interval: no success and all successes are exact at the edge") {
  const auto none = wilson_interval(0, 20);
  CHECK(none.low == 0.0);
  CHECK(std::fabs(none.high - 0.1611) <= 5e-5);
  const auto all = wilson_interval(100, 100);
  CHECK(all.high == 1.0);
  CHECK(std::fabs(all.low - 0.9630) <= 5e-5);
  // Symmetry: x of n and n - x of n mirror each other.
  const auto zero = wilson_interval(0, 100);
  CHECK(zero.high == doctest::Approx(1.0 - all.low));
}

TEST_CASE("Wilson interval: no runs means nothing is known") {
  const auto ci = wilson_interval(0, 0);
  CHECK(ci.low == 0.0);
  CHECK(ci.high == 1.0);
}

TEST_CASE("Wilson interval: contains the estimate and narrows with more runs") {
  for (std::uint64_t n : {10U, 100U, 1000U}) {
    const auto ci = wilson_interval(n * 3 / 10, n);
    CHECK(ci.low < 0.3);
    CHECK(ci.high > 0.3);
  }
  const auto small = wilson_interval(30, 100);
  const auto large = wilson_interval(300, 1000);
  CHECK(large.high - large.low < small.high - small.low);
  // A wider z gives a wider interval.
  const auto z99 = wilson_interval(30, 100, 2.5758293035489);
  CHECK(z99.low < small.low);
  CHECK(z99.high > small.high);
}
