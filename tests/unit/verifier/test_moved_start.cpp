// engine/moved_start.hpp: how much of a start merged after a state's
// analysis a pose of that analysis moves with (the share of the leg still
// ahead of it; all of it for a state without a goal), and when two places
// of a robot are close enough to merge into one.
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

TEST_CASE("two places merge when they overlap, not when they are far apart for their spreads") {
  using p3at::verifier::engine::close_enough_to_merge;
  const Eigen::Matrix2d none = Eigen::Matrix2d::Zero();
  const Eigen::Matrix2d sd10cm = 0.01 * Eigen::Matrix2d::Identity();
  // Within 2 cm: always, whatever the spreads.
  CHECK(close_enough_to_merge({0.0, 0.0}, none, {0.015, 0.0}, none));
  // 0.3 m apart with 10 cm spreads each: 2 * (0.1 + 0.1) + 0.02 = 0.42 m allowed.
  CHECK(close_enough_to_merge({0.0, 0.0}, sd10cm, {0.3, 0.0}, sd10cm));
  CHECK_FALSE(close_enough_to_merge({0.0, 0.0}, sd10cm, {0.5, 0.0}, sd10cm));
  // gen_7056's case: a narrow place and one 10 m away.
  CHECK_FALSE(close_enough_to_merge({0.0, 0.0}, 0.005 * Eigen::Matrix2d::Identity(), {7.7, 6.8}, none));
  // Only the spread along the line between them counts: wide across it, narrow along it.
  Eigen::Matrix2d across = Eigen::Matrix2d::Zero();
  across(1, 1) = 1.0;
  CHECK_FALSE(close_enough_to_merge({0.0, 0.0}, across, {0.5, 0.0}, across));
  CHECK(close_enough_to_merge({0.0, 0.0}, across, {0.0, 0.5}, across));
}
