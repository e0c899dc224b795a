// The schemas are generic over the scalar type: with Eigen's AutoDiffScalar they
// give derivatives that match central finite differences of the double version.

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "p3at/executive/behaviors.hpp"
#include "p3at/executive/schemas.hpp"
#include "p3at/executive/sonar.hpp"

using p3at::exec::Vec2;
using doctest::Approx;

namespace {

using Ad2 = Eigen::AutoDiffScalar<Eigen::Vector2d>;
using Ad3 = Eigen::AutoDiffScalar<Eigen::Vector3d>;
using AdX = Eigen::AutoDiffScalar<Eigen::VectorXd>;

/// Central difference of f along input `i` of x.
template <std::size_t N>
double central_difference(const std::function<double(const std::array<double, N>&)>& f, std::array<double, N> x,
                          std::size_t i, double h = 1e-6) {
  std::array<double, N> plus = x, minus = x;
  plus[i] += h;
  minus[i] -= h;
  return (f(plus) - f(minus)) / (2.0 * h);
}

void check_move_to_guarded_at(double px, double py) {
  const double gx = 4.0, gy = 3.0, dropoff = 2.5, dead = 0.05, gain = 1.3;
  const Ad2 x(px, 2, 0), y(py, 2, 1);
  const Vec2<Ad2> out = p3at::exec::move_to_guarded(Vec2<Ad2>{x, y}, Vec2<Ad2>{Ad2(gx), Ad2(gy)}, dropoff, dead, gain);
  for (int component = 0; component < 2; ++component) {
    const std::function<double(const std::array<double, 2>&)> f = [&](const std::array<double, 2>& p) {
      const Vec2<double> v = p3at::exec::move_to_guarded(Vec2<double>{p[0], p[1]}, Vec2<double>{gx, gy}, dropoff, dead, gain);
      return component == 0 ? v.x : v.y;
    };
    const Ad2& ad = component == 0 ? out.x : out.y;
    CHECK(ad.value() == Approx(f({px, py})));
    for (std::size_t i = 0; i < 2; ++i) {
      CAPTURE(component);
      CAPTURE(i);
      CHECK(ad.derivatives()[static_cast<Eigen::Index>(i)] == Approx(central_difference<2>(f, {px, py}, i)).epsilon(1e-5));
    }
  }
}

}  // namespace

TEST_CASE("move_to_guarded: AutoDiff derivatives match finite differences") {
  SUBCASE("outside the dropoff radius (unit vector only)") { check_move_to_guarded_at(0.0, 0.0); }
  SUBCASE("inside the dropoff radius (ramp)") { check_move_to_guarded_at(3.0, 2.0); }
  SUBCASE("derivatives are not trivially zero outside the dropoff") {
    const Ad2 x(0.0, 2, 0), y(0.0, 2, 1);
    const Vec2<Ad2> out = p3at::exec::move_to_guarded(Vec2<Ad2>{x, y}, Vec2<Ad2>{Ad2(4.0), Ad2(3.0)}, 2.5, 0.05, 1.0);
    // d/dy of the x component of (g - p)/|g - p| at p = 0: (gx gy) / d^3 = 12 / 125.
    CHECK(out.x.derivatives()[1] == Approx(12.0 / 125.0));
  }
}

TEST_CASE("vector_to_velocity: AutoDiff derivatives match finite differences") {
  const double vmax = 0.3, wmax = 0.75, gain = 0.5;  // a low gain keeps rotation unclamped
  const std::array<double, 3> points[] = {{0.5, 0.3, 0.2}, {0.2, -0.4, 0.1}, {0.6, 0.1, 2.0 * 3.14159265358979 + 0.3}};
  for (const auto& at : points) {
    const Ad3 vx(at[0], 3, 0), vy(at[1], 3, 1), heading(at[2], 3, 2);
    const auto out = p3at::exec::vector_to_velocity(Vec2<Ad3>{vx, vy}, heading, vmax, wmax, gain);
    const std::function<double(const std::array<double, 3>&)> trans = [&](const std::array<double, 3>& p) {
      return p3at::exec::vector_to_velocity(Vec2<double>{p[0], p[1]}, p[2], vmax, wmax, gain).trans_mps;
    };
    const std::function<double(const std::array<double, 3>&)> rot = [&](const std::array<double, 3>& p) {
      return p3at::exec::vector_to_velocity(Vec2<double>{p[0], p[1]}, p[2], vmax, wmax, gain).rot_radps;
    };
    CHECK(out.trans_mps.value() == Approx(trans(at)));
    CHECK(out.rot_radps.value() == Approx(rot(at)));
    for (std::size_t i = 0; i < 3; ++i) {
      CAPTURE(i);
      const auto e = static_cast<Eigen::Index>(i);
      CHECK(out.trans_mps.derivatives()[e] == Approx(central_difference<3>(trans, at, i)).epsilon(1e-5));
      CHECK(out.rot_radps.derivatives()[e] == Approx(central_difference<3>(rot, at, i)).epsilon(1e-5));
    }
    // d(rot)/d(heading) = -gain while unclamped.
    CHECK(out.rot_radps.derivatives()[2] == Approx(-gain));
  }
}

TEST_CASE("GoToGuarded with dynamic-size AutoDiff (zero-derivative constants mix in)") {
  p3at::mission::GoToGuardedParams p;
  p.goal = {3.0, 1.0};
  p.noise_gain = 0.2;
  const AdX x(1.0, 2, 0), y(0.5, 2, 1);
  // Obstacles and noise are constants (no derivatives): they must combine cleanly.
  const std::vector<Vec2<AdX>> obstacles{Vec2<AdX>{AdX(1.5), AdX(1.4)}};
  const Vec2<AdX> noise{AdX(0.0), AdX(1.0)};
  const Vec2<AdX> v = p3at::exec::go_to_guarded_vector<AdX>(p, Vec2<AdX>{x, y}, obstacles, noise, 0.4);
  const std::function<double(const std::array<double, 2>&)> fx = [&](const std::array<double, 2>& q) {
    const std::vector<Vec2<double>> obs{Vec2<double>{1.5, 1.4}};
    return p3at::exec::go_to_guarded_vector<double>(p, Vec2<double>{q[0], q[1]}, obs, Vec2<double>{0.0, 1.0}, 0.4).x;
  };
  CHECK(v.x.value() == Approx(fx({1.0, 0.5})));
  REQUIRE(v.x.derivatives().size() == 2);
  CHECK(v.x.derivatives()[0] == Approx(central_difference<2>(fx, {1.0, 0.5}, 0)).epsilon(1e-5));
  CHECK(v.x.derivatives()[1] == Approx(central_difference<2>(fx, {1.0, 0.5}, 1)).epsilon(1e-5));
}

TEST_CASE("sonar_obstacles is generic too: derivative of a point w.r.t. the robot's heading") {
  std::array<double, 16> ranges{};
  ranges.fill(-1.0);
  ranges[3] = 1.0;
  const p3at::exec::Pose<Ad3> pose{Ad3(1.0, 3, 0), Ad3(2.0, 3, 1), Ad3(0.5, 3, 2)};
  const auto obstacles = p3at::exec::sonar_obstacles<Ad3>(ranges, pose);
  REQUIRE(obstacles.count == 1);
  const auto point_x = [&](double th) {
    p3at::exec::Pose<double> q{1.0, 2.0, th};
    return p3at::exec::sonar_obstacles<double>(ranges, q).points[0].x;
  };
  CHECK(obstacles.points[0].x.derivatives()[0] == Approx(1.0));
  CHECK(obstacles.points[0].x.derivatives()[2] == Approx((point_x(0.5 + 1e-6) - point_x(0.5 - 1e-6)) / 2e-6).epsilon(1e-5));
}
