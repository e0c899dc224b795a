// engine/moved_start.hpp: how much of a start merged after a state's
// analysis a pose of that analysis moves with (the share of the leg still
// ahead of it; all of it for a state without a goal).
#include <doctest/doctest.h>

#include <optional>

#include "engine/moved_start.hpp"

using p3at::verifier::engine::share_still_ahead;

TEST_CASE("a state without a goal moves entirely with its start") {
  const Eigen::Vector2d start(1.0, 2.0);
  CHECK(share_still_ahead(start, std::nullopt, start) == doctest::Approx(1.0));
  CHECK(share_still_ahead(start, std::nullopt, Eigen::Vector2d(5.0, -3.0)) == doctest::Approx(1.0));
}

TEST_CASE("along a leg to a goal the share still ahead falls from 1 at the start to 0 at the goal") {
  const Eigen::Vector2d start(0.0, 0.0);
  const std::optional<Eigen::Vector2d> goal = Eigen::Vector2d(10.0, 0.0);
  CHECK(share_still_ahead(start, goal, start) == doctest::Approx(1.0));
  CHECK(share_still_ahead(start, goal, Eigen::Vector2d(2.5, 0.0)) == doctest::Approx(0.75));
  // Off the line, the progress is the projection on the leg.
  CHECK(share_still_ahead(start, goal, Eigen::Vector2d(5.0, 1.5)) == doctest::Approx(0.5));
  CHECK(share_still_ahead(start, goal, *goal) == doctest::Approx(0.0));
  // Past the goal (an overshoot) nothing is left ahead; behind the start
  // (a path that first backs off) the whole leg is.
  CHECK(share_still_ahead(start, goal, Eigen::Vector2d(10.4, 0.0)) == doctest::Approx(0.0));
  CHECK(share_still_ahead(start, goal, Eigen::Vector2d(-0.3, 0.2)) == doctest::Approx(1.0));
}

TEST_CASE("a leg that starts on its goal has no way ahead: its poses move with the start") {
  const Eigen::Vector2d start(3.0, 4.0);
  CHECK(share_still_ahead(start, start, Eigen::Vector2d(3.01, 4.0)) == doctest::Approx(1.0));
}
