// Where a driving teammate's body is at each of the analysed robot's cycles
// (engine/moving_bodies.hpp): along its mean path by the time since its
// entry, its error interpolated along the distance driven, then parked while
// it holds still, on along a next leg, or gone; and the exact distance test
// the path stepper's fast path uses.
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

TEST_CASE("a driving teammate is placed by the time since its entry, with its error along the distance") {
  const std::vector<PathSample> path = straight(0.0, 0.0, 10.0, 10.0);
  TeammateLeg leg = leg_on(path);
  leg.entered_s = -2.0;  // it has driven 2 s when the analysed robot enters
  leg.ends_in_s = 8.0;
  leg.error_end = Eigen::Vector3d(0.0, 1.0, 0.0);  // 1 m to the left by the end
  leg.still_for_s = kInf;                           // parks for good
  const MovingBody body = follow_legs({leg}, 0.1);
  REQUIRE(body.at(0) != nullptr);
  CHECK(body.at(0)->x_m == doctest::Approx(2.0));
  CHECK(body.at(0)->y_m == doctest::Approx(0.2));
  CHECK(body.at(30)->x_m == doctest::Approx(5.0));  // 3 s later: half way
  CHECK(body.at(30)->y_m == doctest::Approx(0.5));
  CHECK(body.at(30)->theta_rad == doctest::Approx(0.0));
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
    CHECK(body.at(49) != nullptr);
    CHECK(body.at(50) == nullptr);
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
    CHECK(body.at(75)->x_m == doctest::Approx(6.5));  // 1.5 s into the next leg
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
  // At cycle 40 the body (626 x 505 mm, heading +x) is centred at (4, 0): a
  // point 0.5 m to its side is 0.2475 m from its outline.
  CHECK(bodies.within(40, 4.0, 0.5, 0.25));
  CHECK_FALSE(bodies.within(40, 4.0, 0.5, 0.24));
  CHECK_FALSE(bodies.within(0, 4.0, 0.5, 0.25));  // at the start it was 4 m away
  std::vector<Segment> seen;
  bodies.append_within(40, 4.0, 0.5, 0.25, seen);
  CHECK(seen.size() == 4);
  seen.clear();
  bodies.append_within(0, 4.0, 0.5, 0.25, seen);
  CHECK(seen.empty());
  CHECK(distance_to_body({0.0, 0.0, 0.0}, 1.0, 0.0) == doctest::Approx(1.0 - 0.313));
  // A way from (5, 2.3) up: the body's centre passes 2.3 m from it, its
  // outline within 2 m (the half-diagonal is 0.402 m); from (5, 2.5) not.
  CHECK(passes_near(follow_legs({leg}, 0.1), 5.0, 2.3, 5.0, 10.0, 2.0));
  CHECK_FALSE(passes_near(follow_legs({leg}, 0.1), 5.0, 2.5, 5.0, 10.0, 2.0));
}
