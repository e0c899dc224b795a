// The first NOISE draw of a leg entered from several start points
// (engine/noise_segments.cpp, noise_quadrature): the executive draws NOISE's
// direction uniformly whatever the pose it starts from, so every direction
// of the quadrature must carry 1 / directions of the probability, however
// the start points are weighted. Dealing the directions out among start
// points of unequal weight (a robot facing about, whose few points that turn
// the other way weigh less) gave the heavy points' directions most of the
// mass: gen_7016's second leg drew four of its eight directions with 97 % of
// it (test_turn_about_entry_cli.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "engine/noise_segments.hpp"
#include "engine/path_stepper.hpp"
#include "engine/state_analysis.hpp"
#include "p3at/verifier/models.hpp"

#include "one_leg_mission.hpp"

using namespace p3at;
using namespace p3at::verifier;
using namespace p3at::verifier::engine;

namespace {

constexpr std::size_t kDirections = 8;

/// Start walkers a few degrees apart in heading, with the given weights.
std::vector<Walker> starts_weighted(const std::vector<double>& weights) {
  std::vector<Walker> out;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    Walker w;
    w.q.theta_rad = 0.05 * static_cast<double>(i);
    w.before = w.q;
    w.weight = weights[i];
    out.push_back(w);
  }
  return out;
}

/// The probability each NOISE direction of the first draw carries, over the
/// paths that finished (all of them on this open-floor leg).
std::vector<double> mass_per_direction(const std::vector<double>& start_weights, std::size_t* paths = nullptr) {
  // A 3 m leg with a NOISE held for the whole of it (one draw).
  const mission::Mission m = test::one_leg_mission(3.0, 0.5, 0.15, 100000);
  Models models;
  RobotModel model;
  model.name = "r";
  models.robots.push_back(model);
  StateContext ctx;
  ctx.robot = &m.robots.front();
  ctx.model = &models.robots.front();
  ctx.models = &models;
  const PathStepper stepper(ctx, 0);
  const NoiseQuadrature quad =
      noise_quadrature(stepper, starts_weighted(start_weights), 100000, kDirections, kDirections, kDirections, 2000);
  REQUIRE(quad.redraws == 0);
  CHECK(quad.stuck == doctest::Approx(0.0));
  std::vector<double> mass(kDirections, 0.0);
  for (const FinishedPath& p : quad.finished) {
    REQUIRE(p.direction < kDirections);
    mass[p.direction] += p.walker.weight;
  }
  if (paths != nullptr) *paths = quad.finished.size();
  return mass;
}

void check_uniform(const std::vector<double>& mass) {
  double total = 0.0;
  for (std::size_t d = 0; d < mass.size(); ++d) {
    CAPTURE(d);
    CHECK(mass[d] == doctest::Approx(1.0 / kDirections).epsilon(1e-9));
    total += mass[d];
  }
  CHECK(total == doctest::Approx(1.0).epsilon(1e-12));
}

}  // namespace

TEST_CASE("start points of equal weight that divide the directions evenly are dealt one share each") {
  std::size_t paths = 0;
  check_uniform(mass_per_direction({0.25, 0.25, 0.25, 0.25}, &paths));
  CHECK(paths == kDirections);  // dealt: the cost of one start point
}

TEST_CASE("start points of unequal weight: every start takes every direction, each direction 1/8 of the mass") {
  // The facing-about robot's entry: a light point that turns the other way.
  std::size_t paths = 0;
  check_uniform(mass_per_direction({0.033, 0.033, 0.467, 0.467}, &paths));
  CHECK(paths == 4 * kDirections);
  // Weights that do not sum to one are normalised first.
  check_uniform(mass_per_direction({1.0, 3.0}));
}

TEST_CASE("equal start points that do not divide the directions (3 of 8): every start takes every direction") {
  // Dealt, three starts would share 3, 3 and 2 directions: 1/9 against 1/6.
  std::size_t paths = 0;
  check_uniform(mass_per_direction({1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, &paths));
  CHECK(paths == 3 * kDirections);
}
