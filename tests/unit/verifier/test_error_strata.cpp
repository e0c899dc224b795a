// The entry error split into strata where a wall is within reach of its
// tail (engine/error_strata.hpp): the slabs' numbers from the normal
// distribution, the axis the split is taken along, when it is not taken, and
// that the split keeps the error's mean and covariance.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <Eigen/Cholesky>

#include "engine/error_strata.hpp"
#include "engine/path_stepper.hpp"

namespace engine = p3at::verifier::engine;

namespace {

engine::BaseState at(double x, double y, double theta) {
  engine::BaseState q;
  q.x_m = x;
  q.y_m = y;
  q.theta_rad = theta;
  return q;
}

p3at::mission::GoToGuardedParams leg_to(double x, double y) {
  p3at::mission::GoToGuardedParams go;
  go.goal.x_m = x;
  go.goal.y_m = y;
  return go;
}

engine::ErrorState error_with(double sx, double sy, double stheta) {
  engine::ErrorState e;
  e.cov = Eigen::Vector3d(sx * sx, sy * sy, stheta * stheta).asDiagonal();
  return e;
}

}  // namespace

TEST_CASE("the strata are slabs of the standard normal at their conditional means") {
  const auto& s = engine::error_strata();
  double total = 0.0, mean = 0.0;
  for (const auto& k : s) {
    total += k.weight;
    mean += k.weight * k.z;
  }
  CHECK(total == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(mean) < 1e-12);
  // The middle slab |z| < 0.75 and the tail beyond 2.25: closed forms.
  CHECK(s[0].z == 0.0);
  CHECK(s[0].weight == doctest::Approx(0.546745).epsilon(1e-5));
  const double phi = std::exp(-0.5 * 2.25 * 2.25) / std::sqrt(2.0 * 3.14159265358979323846);
  CHECK(s[5].weight == doctest::Approx(0.0122245).epsilon(1e-4));
  CHECK(s[5].z == doctest::Approx(phi / s[5].weight).epsilon(1e-9));
  CHECK(s[6].z == doctest::Approx(-s[5].z));
  // Between them they carry most of the variance, never more than all of it.
  CHECK(engine::strata_variance() > 0.85);
  CHECK(engine::strata_variance() < 1.0);
}

TEST_CASE("the axis is the error that moves the leg sideways the most, and only near a wall") {
  // A 10 m leg along x from the origin; a wall along y = 1.2 beside it.
  const std::vector<engine::Segment> wall{{0.0, 1.2, 10.0, 1.2}};
  const auto go = leg_to(10.0, 0.0);
  const double reach = 1.0;
  SUBCASE("a heading error: the axis is the heading's sd") {
    const auto axis = engine::wall_sensitive_axis(at(0, 0, 0), go, error_with(0.0, 0.0, 0.02), wall, reach);
    REQUIRE(axis.has_value());
    CHECK(std::abs((*axis)(2)) == doctest::Approx(0.02));
    CHECK(std::abs((*axis)(0)) < 1e-12);
  }
  SUBCASE("a sideways error larger than what the heading makes of it: the axis is sideways") {
    const auto axis = engine::wall_sensitive_axis(at(0, 0, 0), go, error_with(0.01, 0.3, 0.001), wall, reach);
    REQUIRE(axis.has_value());
    CHECK(std::abs((*axis)(1)) == doctest::Approx(0.3).epsilon(0.01));
  }
  SUBCASE("no wall within reach of the error's tail: no split") {
    const std::vector<engine::Segment> far{{0.0, 5.0, 10.0, 5.0}};
    CHECK_FALSE(engine::wall_sensitive_axis(at(0, 0, 0), go, error_with(0.0, 0.2, 0.0), far, reach).has_value());
    // The same wall is found when the error's tail reaches it (3 sd of 1.4 m).
    CHECK(engine::wall_sensitive_axis(at(0, 0, 0), go, error_with(0.0, 1.4, 0.0), far, reach).has_value());
  }
  SUBCASE("an error too small to move the leg by 2 cm: no split") {
    CHECK_FALSE(engine::wall_sensitive_axis(at(0, 0, 0), go, error_with(0.0, 0.005, 0.0005), wall, reach).has_value());
  }
  SUBCASE("the wall is looked for beside the leg moved by the error's mean") {
    engine::ErrorState e = error_with(0.0, 0.1, 0.0);
    const std::vector<engine::Segment> above{{0.0, 3.0, 10.0, 3.0}};
    CHECK_FALSE(engine::wall_sensitive_axis(at(0, 0, 0), go, e, above, reach).has_value());
    e.mean(1) = 1.8;  // the true leg runs at y = 1.8, within reach of y = 3
    CHECK(engine::wall_sensitive_axis(at(0, 0, 0), go, e, above, reach).has_value());
  }
}

TEST_CASE("the split keeps the walker's weight, its error's mean and its covariance") {
  engine::Walker w;
  w.weight = 0.25;
  w.error.mean = Eigen::Vector3d(0.1, -0.2, 0.05);
  Eigen::Matrix3d c;
  c << 0.010, 0.002, 0.0005, 0.002, 0.040, 0.001, 0.0005, 0.001, 0.0009;
  w.error.cov = c;
  // 1 sd of the covariance along some direction: S u with |u| = 1.
  const Eigen::Vector3d axis = c * Eigen::Vector3d(0.0, 1.0, 0.0) / std::sqrt(c(1, 1));
  const auto strata = engine::split_into_strata({w}, axis);
  REQUIRE(strata.size() == engine::kErrorStrata);
  double weight = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& s : strata) {
    weight += s.weight;
    mean += s.weight * s.error.mean;
  }
  CHECK(weight == doctest::Approx(0.25));
  mean /= weight;
  CHECK((mean - w.error.mean).norm() < 1e-12);
  Eigen::Matrix3d total = Eigen::Matrix3d::Zero();
  for (const auto& s : strata) {
    const Eigen::Vector3d d = s.error.mean - w.error.mean;
    total += s.weight / weight * (s.error.cov + d * d.transpose());
  }
  CHECK((total - c).norm() < 1e-12);
  // Every stratum's own covariance is still one (no negative variance).
  for (const auto& s : strata) {
    CHECK(s.error.cov.ldlt().isPositive());
    CHECK(s.stratum < engine::kErrorStrata);
  }
  CHECK(strata[0].stratum == 0);
  CHECK(strata[0].error.mean == w.error.mean);
}

