// Where a teammate's body is at each of the analysed robot's cycles
// (engine/moving_bodies.hpp): absent while it drives, parked at its end pose
// (with its error) while it holds still, then on along a next leg, or gone;
// and the exact distance test the path stepper's fast path uses.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/moving_bodies.hpp"

using namespace p3at::verifier::engine;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// 1 m/s along +x from (x0, y) for `seconds`, then standing (samples every second).
std::vector<PathSample> straight(double x0, double y, double seconds, double total_s) {
  std::vector<PathSample> path;
  for (int k = 0; k <= static_cast<int>(total_s); ++k) {
    path.push_back({static_cast<double>(k), x0 + std::min(static_cast<double>(k), seconds), y});
  }
  return path;
}

TeammateLeg leg_on(const std::vector<PathSample>& path) {
  TeammateLeg leg;
  leg.path = &path;
  leg.start = {path.front().x_m, path.front().y_m, 0.0, 0.0, 0.0};
  leg.end = {path.back().x_m, path.back().y_m, 0.0, 0.0, 0.0};
  return leg;
}

}  // namespace

// Teammates are obstacles only where they stand still (moving_bodies.cpp,
// kBodiesWhileDriving: driving mean bodies were measured worse), so a body
// is absent while its leg is driven.
TEST_CASE("a driving teammate is no obstacle until it parks, at its end pose with its error") {
  const std::vector<PathSample> path = straight(0.0, 0.0, 10.0, 10.0);
  TeammateLeg leg = leg_on(path);
  leg.entered_s = -2.0;  // it has driven 2 s when the analysed robot enters
  leg.ends_in_s = 8.0;
  leg.error_end = Eigen::Vector3d(0.0, 1.0, 0.0);  // 1 m to the left by the end
  leg.still_for_s = kInf;                           // parks for good
  const MovingBody body = follow_legs({leg}, 0.1);
  CHECK(body.at(0) == nullptr);   // driving
  CHECK(body.at(30) == nullptr);
  CHECK(body.at(79) == nullptr);  // its leg ends 8 s after the analysed robot's entry
  // Parked at its end pose for good once its leg has ended.
  REQUIRE(body.at(100000) != nullptr);
  CHECK(body.at(100000)->x_m == doctest::Approx(10.0));
  CHECK(body.at(100000)->y_m == doctest::Approx(1.0));
}

TEST_CASE("after its leg a teammate stays while it holds still, then drops out unless its next leg is given") {
  const std::vector<PathSample> path = straight(0.0, 0.0, 5.0, 5.0);
  TeammateLeg leg = leg_on(path);
  leg.ends_in_s = 5.0;
  SUBCASE("its next state is a leg: gone when the leg ends") {
    leg.still_for_s = 0.0;
    const MovingBody body = follow_legs({leg}, 0.1);
    CHECK(body.at(10) == nullptr);  // driving
    CHECK(body.at(50) == nullptr);  // gone
  }
  SUBCASE("a 2 s still state first: there until 7 s, at its end") {
    leg.still_for_s = 2.0;
    const MovingBody body = follow_legs({leg}, 0.1);
    REQUIRE(body.at(69) != nullptr);
    CHECK(body.at(69)->x_m == doctest::Approx(5.0));
    CHECK(body.at(70) == nullptr);
  }
  SUBCASE("no self-timed exit: it waits at the end of its path for good") {
    leg.ends_in_s = kInf;
    const MovingBody body = follow_legs({leg}, 0.1);
    REQUIRE(body.at(5000) != nullptr);
    CHECK(body.at(5000)->x_m == doctest::Approx(5.0));
  }
  SUBCASE("then its next leg (predicted ahead), on which it parks") {
    leg.still_for_s = 1.0;
    const std::vector<PathSample> next_path = straight(5.0, 0.0, 3.0, 4.0);
    TeammateLeg next = leg_on(next_path);
    next.entered_s = 6.0;
    next.ends_in_s = 10.0;
    next.still_for_s = kInf;
    const MovingBody body = follow_legs({leg, next}, 0.1);
    CHECK(body.at(55)->x_m == doctest::Approx(5.0));  // holding still between the legs
    CHECK(body.at(75) == nullptr);  // driving its next leg
    REQUIRE(body.at(100000) != nullptr);
    CHECK(body.at(100000)->x_m == doctest::Approx(8.0));
  }
}

TEST_CASE("bodies within reach are found by their outline, not their centre, at the cycle asked") {
  const std::vector<PathSample> path = straight(0.0, 0.0, 10.0, 10.0);
  TeammateLeg leg = leg_on(path);
  leg.ends_in_s = 10.0;
  leg.still_for_s = kInf;
  MovingBodies bodies;
  bodies.add(follow_legs({leg}, 0.1));
  // Parked from cycle 100 (626 x 505 mm, heading +x) centred at (10, 0): a
  // point 0.5 m to its side is 0.2475 m from its outline.
  CHECK(bodies.within(150, 10.0, 0.5, 0.25));
  CHECK_FALSE(bodies.within(150, 10.0, 0.5, 0.24));
  CHECK_FALSE(bodies.within(40, 4.0, 0.5, 0.25));  // driving there then: no obstacle
  std::vector<Segment> seen;
  bodies.append_within(150, 10.0, 0.5, 0.25, seen);
  CHECK(seen.size() == 4);
  seen.clear();
  bodies.append_within(40, 4.0, 0.5, 0.25, seen);
  CHECK(seen.empty());
  CHECK(distance_to_body({0.0, 0.0, 0.0}, 1.0, 0.0) == doctest::Approx(1.0 - 0.313));
  // A way from (10, 2.3) up: the parked body's centre is 2.3 m from it, its
  // outline within 2 m (the half-diagonal is 0.402 m); from (10, 2.5) not.
  CHECK(passes_near(follow_legs({leg}, 0.1), 10.0, 2.3, 10.0, 10.0, 2.0));
  CHECK_FALSE(passes_near(follow_legs({leg}, 0.1), 10.0, 2.5, 10.0, 10.0, 2.0));
}
