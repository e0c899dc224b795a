// Sonar ring → world-frame obstacle points, and the pose algebra behind the
// mission frame.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "p3at/executive/frames.hpp"
#include "p3at/executive/sonar.hpp"

using doctest::Approx;
using P = p3at::exec::Pose<double>;

namespace {
std::array<double, 16> no_readings() {
  std::array<double, 16> r{};
  r.fill(-1.0);
  return r;
}
}  // namespace

TEST_CASE("sonar_obstacles: a forward sonar at the origin, robot facing +x") {
  auto r = no_readings();
  r[3] = 1.0;  // sonar 3: (0.245, 0.027) facing +10°
  const auto obs = p3at::exec::sonar_obstacles<double>(r, P{0, 0, 0});
  REQUIRE(obs.count == 1);
  const double a = 10.0 * std::numbers::pi / 180.0;
  CHECK(obs.points[0].x == Approx(0.245 + std::cos(a)));
  CHECK(obs.points[0].y == Approx(0.027 + std::sin(a)));
}

TEST_CASE("sonar_obstacles: side sonar, robot rotated and translated") {
  auto r = no_readings();
  r[0] = 2.0;  // sonar 0: (0.147, 0.136) facing +90° (left)
  // Robot at (5, 5) facing +y: its left is -x.
  const auto obs = p3at::exec::sonar_obstacles<double>(r, P{5.0, 5.0, std::numbers::pi / 2});
  REQUIRE(obs.count == 1);
  // Robot-frame point (0.147, 2.136) → world (5 - 2.136, 5 + 0.147).
  CHECK(obs.points[0].x == Approx(5.0 - 2.136));
  CHECK(obs.points[0].y == Approx(5.147));
}

TEST_CASE("sonar_obstacles: a rear sonar") {
  auto r = no_readings();
  r[8] = 0.5;  // sonar 8: (-0.144, -0.136) facing -90°
  const auto obs = p3at::exec::sonar_obstacles<double>(r, P{0, 0, 0});
  REQUIRE(obs.count == 1);
  CHECK(obs.points[0].x == Approx(-0.144));
  CHECK(obs.points[0].y == Approx(-0.636));
}

TEST_CASE("sonar_obstacles: skips no-reading, max-range and non-finite values") {
  auto r = no_readings();
  r[0] = 5.0;                                        // at max range: nothing seen
  r[1] = 7.5;                                        // beyond
  r[2] = std::numeric_limits<double>::quiet_NaN();   // garbage
  r[4] = std::numeric_limits<double>::infinity();
  r[5] = 4.99;                                       // valid
  r[15] = 0.0;                                       // touching: valid
  const auto obs = p3at::exec::sonar_obstacles<double>(r, P{0, 0, 0});
  CHECK(obs.count == 2);
  CHECK(obs.view().size() == 2);
  const auto shorter = p3at::exec::sonar_obstacles<double>(r, P{0, 0, 0}, 3.0);
  CHECK(shorter.count == 1);  // 4.99 is beyond a 3 m range
  const auto all = p3at::exec::sonar_obstacles<double>(no_readings(), P{0, 0, 0});
  CHECK(all.count == 0);
}

TEST_CASE("sonar table matches ARIA's p3at.p") {
  CHECK(p3at::exec::kP3atSonars.size() == 16);
  CHECK(p3at::exec::kP3atSonars[0].heading_deg == 90.0);
  CHECK(p3at::exec::kP3atSonars[11].x_m == Approx(-0.241));
  CHECK(p3at::exec::kP3atSonars[12].heading_deg == 170.0);
  CHECK(p3at::exec::kP3atSonars[15].x_m == Approx(-0.144));
}

TEST_CASE("compose and relative are inverse operations") {
  const P a{1.0, 2.0, 0.7};
  const P b{-0.5, 3.0, 2.9};
  const P ab = p3at::exec::compose(a, b);
  const P back = p3at::exec::relative(a, ab);
  CHECK(back.x_m == Approx(b.x_m));
  CHECK(back.y_m == Approx(b.y_m));
  CHECK(back.theta_rad == Approx(b.theta_rad));
  // A known case: 1 m forward from (1, 1) facing +y is (1, 2).
  const P fwd = p3at::exec::compose(P{1, 1, std::numbers::pi / 2}, P{1, 0, 0});
  CHECK(fwd.x_m == Approx(1.0));
  CHECK(fwd.y_m == Approx(2.0));
}

TEST_CASE("wrap_angle_rad") {
  CHECK(p3at::exec::wrap_angle_rad(0.0) == 0.0);
  CHECK(p3at::exec::wrap_angle_rad(3 * std::numbers::pi) == Approx(std::numbers::pi));
  CHECK(p3at::exec::wrap_angle_rad(-std::numbers::pi) == Approx(std::numbers::pi));
  CHECK(p3at::exec::wrap_angle_rad(2 * std::numbers::pi + 0.1) == Approx(0.1));
  CHECK(p3at::exec::wrap_angle_rad(-0.1 - 4 * std::numbers::pi) == Approx(-0.1));
}
