// The first NOISE draw's outcomes placed on the circle (engine/direction_arcs.hpp):
// a direction's share is the arc over which its outcome holds, located by
// bisection to the resolution asked, within the probe budget, and the
// equal shares wherever neighbours agree.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "engine/direction_arcs.hpp"

namespace engine = p3at::verifier::engine;

namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

/// `n` equally spaced angles as the quadrature lays them (half a spacing in).
std::vector<double> circle(std::size_t n) {
  std::vector<double> a;
  for (std::size_t j = 0; j < n; ++j) a.push_back(kTwoPi * (static_cast<double>(j) + 0.5) / static_cast<double>(n));
  return a;
}

/// Fires exit 0 on [lo, hi) of the circle (radians, lo < hi < 2 pi), runs on elsewhere.
engine::DrawProbe fires_between(double lo, double hi, std::size_t& calls) {
  return [lo, hi, &calls](double angle) {
    ++calls;
    const double a = std::fmod(angle, kTwoPi);
    return a >= lo && a < hi ? engine::draw_fired(0) : engine::kDrawRunning;
  };
}

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

}  // namespace

TEST_CASE("an arc of one outcome is located to the bisection's resolution") {
  const std::vector<double> angles = circle(8);
  // Fired over 60 degrees around direction 0 (at 22.5 degrees): it and no
  // other direction fire, so the equal shares give it 1/8 = 45 degrees.
  const double lo = 0.01, hi = 0.01 + 60.0 * kTwoPi / 360.0;
  std::size_t calls = 0;
  const engine::DrawProbe probe = fires_between(lo, hi, calls);
  std::vector<engine::DrawOutcome> outcomes;
  for (const double a : angles) outcomes.push_back(probe(a));
  calls = 0;
  REQUIRE(outcomes[0] == engine::draw_fired(0));
  REQUIRE(outcomes[1] == engine::kDrawRunning);
  std::size_t probes = 0;
  const engine::DirectionArcLimits limits;
  const std::vector<double> share = engine::direction_arcs(angles, outcomes, probe, limits, probes);
  CHECK(sum(share) == doctest::Approx(1.0).epsilon(1e-12));
  // Each of its two boundaries within half the last bracket: spacing / 2^(depth+1).
  const double resolution = (1.0 / 8.0) / std::pow(2.0, static_cast<double>(limits.depth) + 1.0);
  CHECK(std::abs(share[0] - (hi - lo) / kTwoPi) <= 2.0 * resolution + 1e-12);
  CHECK(std::abs(share[0] - 1.0 / 8.0) > 2.0 * resolution);  // the equal share was that far off
  // Two boundaries, `depth` probes each; the agreeing neighbours keep the
  // midpoints, so the directions beyond them keep the equal share.
  CHECK(probes == 2 * limits.depth);
  CHECK(calls == probes);
  for (std::size_t j = 3; j <= 6; ++j) CHECK(share[j] == doctest::Approx(1.0 / 8.0));

  // The boundaries (engine/held_duration times the arcs by them): the arc
  // of direction 0 is between the last one and the first, near lo and hi.
  std::vector<double> boundaries;
  std::size_t again = 0;
  const std::vector<double> same = engine::direction_arcs(angles, outcomes, probe, limits, again, &boundaries);
  REQUIRE(boundaries.size() == 8);
  CHECK(same == share);
  CHECK(std::abs(boundaries[0] - hi) <= resolution * kTwoPi + 1e-12);
  CHECK(std::abs(boundaries[7] - kTwoPi - lo) <= resolution * kTwoPi + 1e-12);
  for (std::size_t j = 0; j < 8; ++j) {
    const double left = j == 0 ? boundaries[7] - kTwoPi : boundaries[j - 1];
    CHECK((boundaries[j] - left) / kTwoPi == doctest::Approx(share[j]).epsilon(1e-12));
  }
}

TEST_CASE("the arc across the wrap of the circle") {
  const std::vector<double> angles = circle(8);
  // Pinned from 300 to 360 degrees and from 0 to 10 (the last and the first
  // directions, at 337.5 and 22.5, see different outcomes: 337.5 pinned).
  const auto probe = [](double angle) {
    const double deg = std::fmod(angle, kTwoPi) * 360.0 / kTwoPi;
    return deg >= 300.0 || deg < 10.0 ? engine::kDrawPinned : engine::kDrawRunning;
  };
  std::vector<engine::DrawOutcome> outcomes;
  for (const double a : angles) outcomes.push_back(probe(a));
  std::size_t probes = 0;
  engine::DirectionArcLimits limits;
  limits.depth = 6;
  limits.max_probes = 64;
  const std::vector<double> share = engine::direction_arcs(angles, outcomes, probe, limits, probes);
  CHECK(sum(share) == doctest::Approx(1.0).epsilon(1e-12));
  const double resolution = (1.0 / 8.0) / std::pow(2.0, 7.0);
  CHECK(std::abs(share[7] - 70.0 / 360.0) <= 2.0 * resolution + 1e-12);
}

TEST_CASE("agreeing directions, or no budget, keep the equal shares") {
  const std::vector<double> angles = circle(8);
  std::size_t calls = 0;
  const engine::DrawProbe probe = fires_between(0.0, 1.0, calls);
  std::size_t probes = 0;
  const std::vector<engine::DrawOutcome> same(8, engine::kDrawRunning);
  const std::vector<double> share = engine::direction_arcs(angles, same, probe, {}, probes);
  CHECK(probes == 0);
  CHECK(calls == 0);
  for (const double s : share) CHECK(s == 1.0 / 8.0);

  std::vector<engine::DrawOutcome> mixed(8, engine::kDrawRunning);
  mixed[0] = engine::draw_fired(0);
  engine::DirectionArcLimits none;
  none.max_probes = 0;
  const std::vector<double> unprobed = engine::direction_arcs(angles, mixed, probe, none, probes);
  CHECK(probes == 0);
  for (const double s : unprobed) CHECK(s == doctest::Approx(1.0 / 8.0));

  // The budget is kept: many changes of outcome, few probes.
  std::vector<engine::DrawOutcome> alternating(8);
  for (std::size_t j = 0; j < 8; ++j) alternating[j] = j % 2 == 0 ? engine::kDrawPinned : engine::kDrawRunning;
  engine::DirectionArcLimits few;
  few.max_probes = 5;
  const std::vector<double> budgeted = engine::direction_arcs(angles, alternating, probe, few, probes);
  CHECK(probes == 5);
  CHECK(sum(budgeted) == doctest::Approx(1.0).epsilon(1e-12));
}
