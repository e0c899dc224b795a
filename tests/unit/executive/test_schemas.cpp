// Every motor schema against hand-computed values (docs/executive.md).

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "p3at/executive/behaviors.hpp"
#include "p3at/executive/schemas.hpp"

using p3at::exec::Vec2;
using V = Vec2<double>;
using doctest::Approx;

namespace {
constexpr double kPi = std::numbers::pi;
}

TEST_CASE("move_to_guarded: full gain outside the dropoff radius") {
  // d = 5 > dropoff 2.5: unit vector (0.6, 0.8) times gain 2.
  const V out = p3at::exec::move_to_guarded(V{0, 0}, V{3, 4}, 2.5, 0.05, 2.0);
  CHECK(out.x == Approx(1.2));
  CHECK(out.y == Approx(1.6));
  // Exactly at the dropoff edge the ramp is 1: continuous.
  const V edge = p3at::exec::move_to_guarded(V{1, 1}, V{1 + 1.5, 1 + 2.0}, 2.5, 0.05, 1.0);
  CHECK(std::hypot(edge.x, edge.y) == Approx(1.0));
}

TEST_CASE("move_to_guarded: linear ramp inside the dropoff radius") {
  // d = 2: magnitude (2 - 0.05) / (2.5 - 0.05) = 0.795918...
  const V out = p3at::exec::move_to_guarded(V{0, 0}, V{1.2, 1.6}, 2.5, 0.05, 1.0);
  const double m = 1.95 / 2.45;
  CHECK(out.x == Approx(0.6 * m));
  CHECK(out.y == Approx(0.8 * m));
  // Halfway between dead zone (1) and dropoff (3) with gain 4: magnitude 2, pointing -x.
  const V half = p3at::exec::move_to_guarded(V{5, 0}, V{3, 0}, 3.0, 1.0, 4.0);
  CHECK(half.x == Approx(-2.0));
  CHECK(half.y == Approx(0.0));
}

TEST_CASE("move_to_guarded: zero inside the dead zone") {
  const V at_edge = p3at::exec::move_to_guarded(V{0, 0}, V{0.03, 0.04}, 2.5, 0.05, 1.0);
  CHECK(at_edge.x == 0.0);
  CHECK(at_edge.y == 0.0);
  const V inside = p3at::exec::move_to_guarded(V{2, 2}, V{2.01, 2.0}, 2.5, 0.05, 1.0);
  CHECK(inside.x == 0.0);
  CHECK(inside.y == 0.0);
  // Just outside the dead zone the ramp starts from (almost) zero.
  const V just_out = p3at::exec::move_to_guarded(V{0, 0}, V{0.06, 0}, 2.5, 0.05, 1.0);
  CHECK(just_out.x == Approx(0.01 / 2.45));
}

TEST_CASE("avoid_obstacles: contact, sphere and beyond") {
  const double sphere = 1.0, margin = 0.25, radius = 0.4;  // contact at 0.65 m, influence to 1.65 m
  SUBCASE("inside the sphere: (sphere - (d - c)) / sphere, away from the obstacle") {
    const std::vector<V> obs{V{1.0, 0.0}};
    const V out = p3at::exec::avoid_obstacles<double>(obs, V{0, 0}, sphere, margin, radius, 2.0);
    CHECK(out.x == Approx(-2.0 * 0.65));  // (1 - (1 - 0.65)) / 1 = 0.65, gain 2
    CHECK(out.y == Approx(0.0));
  }
  SUBCASE("inside the safety margin: the large contact constant") {
    const std::vector<V> obs{V{3.0, 1.5}};  // 0.5 m below the robot at (3, 2)
    const V out = p3at::exec::avoid_obstacles<double>(obs, V{3, 2}, sphere, margin, radius, 1.0);
    CHECK(out.x == Approx(0.0));
    CHECK(out.y == Approx(p3at::exec::kContactRepulsion));
  }
  SUBCASE("outside the sphere: nothing") {
    const std::vector<V> obs{V{2.0, 0.0}, V{0.0, -1.7}};
    const V out = p3at::exec::avoid_obstacles<double>(obs, V{0, 0}, sphere, margin, radius, 1.0);
    CHECK(out.x == 0.0);
    CHECK(out.y == 0.0);
  }
  SUBCASE("repulsions add up") {
    const std::vector<V> obs{V{1.0, 0.0}, V{0.0, 1.0}, V{5.0, 5.0}};
    const V out = p3at::exec::avoid_obstacles<double>(obs, V{0, 0}, sphere, margin, radius, 1.0);
    CHECK(out.x == Approx(-0.65));
    CHECK(out.y == Approx(-0.65));
  }
  SUBCASE("an obstacle at the centre has no direction and is skipped") {
    const std::vector<V> obs{V{1.0, 1.0}};
    const V out = p3at::exec::avoid_obstacles<double>(obs, V{1, 1}, sphere, margin, radius, 1.0);
    CHECK(out.x == 0.0);
    CHECK(out.y == 0.0);
  }
}

TEST_CASE("noise and coop") {
  const V n = p3at::exec::noise(V{0.6, 0.8}, 0.5);
  CHECK(n.x == Approx(0.3));
  CHECK(n.y == Approx(0.4));
  const std::array<V, 3> vectors{V{1, 0}, V{0, 2}, V{-1, -1}};
  const V sum = p3at::exec::coop(vectors, std::array<double, 3>{1.0, 0.5, 2.0});
  CHECK(sum.x == Approx(-1.0));  // 1 + 0 - 2
  CHECK(sum.y == Approx(-1.0));  // 0 + 1 - 2
  const V zero_weights = p3at::exec::coop(vectors, std::array<double, 3>{0.0, 0.0, 0.0});
  CHECK(zero_weights.x == 0.0);
  CHECK(zero_weights.y == 0.0);
}

TEST_CASE("vector_to_velocity: heading errors of 0, +90, -90 and 180 degrees") {
  const double vmax = 0.3, wmax = 0.75, k = 1.5;
  SUBCASE("error 0: full speed, capped at |V| = 1; no rotation") {
    const auto half = p3at::exec::vector_to_velocity(V{0.5, 0.0}, 0.0, vmax, wmax, k);
    CHECK(half.trans_mps == Approx(0.15));
    CHECK(half.rot_radps == Approx(0.0));
    const auto big = p3at::exec::vector_to_velocity(V{0.0, 7.0}, kPi / 2, vmax, wmax, k);
    CHECK(big.trans_mps == Approx(0.3));
    CHECK(big.rot_radps == Approx(0.0).epsilon(1e-12));
    // Heading several turns around: the error still wraps to 0.
    const auto turns = p3at::exec::vector_to_velocity(V{std::cos(0.1), std::sin(0.1)}, 4 * kPi + 0.1, vmax, wmax, k);
    CHECK(turns.trans_mps == Approx(0.3));
    CHECK(turns.rot_radps == Approx(0.0).scale(1.0));
  }
  SUBCASE("+90: turn left at the cap, no translation") {
    const auto out = p3at::exec::vector_to_velocity(V{0.0, 1.0}, 0.0, vmax, wmax, k);
    CHECK(out.rot_radps == Approx(0.75));
    CHECK(out.trans_mps == Approx(0.0).scale(1.0));
  }
  SUBCASE("-90: turn right at the cap, no translation") {
    const auto out = p3at::exec::vector_to_velocity(V{0.0, -1.0}, 0.0, vmax, wmax, k);
    CHECK(out.rot_radps == Approx(-0.75));
    CHECK(out.trans_mps == Approx(0.0).scale(1.0));
  }
  SUBCASE("180: rotate (counter-clockwise by convention), no translation") {
    const auto out = p3at::exec::vector_to_velocity(V{-1.0, 0.0}, 0.0, vmax, wmax, k);
    CHECK(out.rot_radps == Approx(0.75));
    CHECK(out.trans_mps == 0.0);
  }
  SUBCASE("30 degrees with an unclamped gain: rot = k × error, trans scaled by cos") {
    const double a = kPi / 6;
    const auto out = p3at::exec::vector_to_velocity(V{0.8 * std::cos(a), 0.8 * std::sin(a)}, 0.0, vmax, wmax, 1.0);
    CHECK(out.rot_radps == Approx(a));
    CHECK(out.trans_mps == Approx(0.3 * 0.8 * std::cos(a)));
  }
  SUBCASE("zero vector: zero command") {
    const auto out = p3at::exec::vector_to_velocity(V{0.0, 0.0}, 1.0, vmax, wmax, k);
    CHECK(out.trans_mps == 0.0);
    CHECK(out.rot_radps == 0.0);
  }
}

TEST_CASE("go_to_guarded: the COOP of the three schemas, weighted by the mission's gains") {
  p3at::mission::GoToGuardedParams p;
  p.goal = {10.0, 0.0};
  p.move_gain = 1.0;
  p.avoid_gain = 2.0;
  p.noise_gain = 0.5;
  p.sphere_m = 1.0;
  p.safety_margin_m = 0.25;
  const std::vector<V> obstacles{V{0.0, 1.0}};  // d = 1 → 0.65 away (−y)
  const V v = p3at::exec::go_to_guarded_vector<double>(p, V{0, 0}, obstacles, V{0.0, 1.0}, 0.4);
  CHECK(v.x == Approx(1.0));                    // move: (1, 0)
  CHECK(v.y == Approx(2.0 * -0.65 + 0.5 * 1.0));  // avoid + noise
  p3at::exec::BehaviorConfig config;
  const auto cmd = p3at::exec::go_to_guarded<double>(p, p3at::exec::Pose<double>{0, 0, 0}, obstacles, V{0.0, 1.0}, config);
  const auto expected = p3at::exec::vector_to_velocity(v, 0.0, config.max_speed_mps, config.max_rot_radps, config.rot_gain);
  CHECK(cmd.trans_mps == Approx(expected.trans_mps));
  CHECK(cmd.rot_radps == Approx(expected.rot_radps));
  CHECK(cmd.rot_radps < 0.0);  // the net vector points below the x axis
}

TEST_CASE("spin_command: the mission's rate, limited to the rotational cap") {
  p3at::exec::BehaviorConfig config;
  const auto slow = p3at::exec::spin_command(p3at::mission::SpinParams{30.0}, config);
  CHECK(slow.trans_mps == 0.0);
  CHECK(slow.rot_radps == Approx(30.0 * kPi / 180.0));
  const auto fast = p3at::exec::spin_command(p3at::mission::SpinParams{-90.0}, config);
  CHECK(fast.rot_radps == Approx(-config.max_rot_radps));
}
