#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "p3at/bridge/accessories/heading_fuser.hpp"

using p3at::bridge::HeadingFuser;
using p3at::hal::Pose2;

TEST_CASE("the first update adopts the odometry pose") {
  HeadingFuser f;
  const Pose2 p = f.update(Pose2{1.0, 2.0, 0.5}, 7.0, 0);
  CHECK(p.x_m == 1.0);
  CHECK(p.y_m == 2.0);
  CHECK(p.theta_rad == 0.5);
}

TEST_CASE("turning in place, the gyro's heading change dominates slipping odometry") {
  HeadingFuser f;
  // Odometry over-reports turns by 15 % (skid), the gyro is right.
  double truth = 0.0;
  std::int64_t t = 0;
  f.update(Pose2{}, 0.0, t);
  for (int i = 0; i < 100; ++i) {  // 10 s at 0.6 rad/s
    truth += 0.06;
    t += 100'000;
    f.update(Pose2{0.0, 0.0, 1.15 * truth}, truth, t);
  }
  CHECK(f.pose().theta_rad == doctest::Approx(truth).epsilon(0.01));
  CHECK(f.last_gyro_weight() > 0.99);
}

TEST_CASE("standing still, the odometry's zero change dominates gyro drift") {
  HeadingFuser f;
  std::int64_t t = 0;
  f.update(Pose2{}, 0.0, t);
  double gyro = 0.0;
  for (int i = 0; i < 600; ++i) {  // 60 s with 0.002 rad/s of residual drift
    gyro += 0.0002;
    t += 100'000;
    f.update(Pose2{}, gyro, t);
  }
  CHECK(std::fabs(f.pose().theta_rad) < 0.005);
  CHECK(f.last_gyro_weight() < 0.01);
}

TEST_CASE("position is re-integrated along the fused heading, reversing included") {
  HeadingFuser f;
  std::int64_t t = 0;
  f.update(Pose2{}, 0.0, t);
  // Odometry believes it turned 90° left then drove 1 m; the gyro says it turned 0.
  t += 100'000;
  f.update(Pose2{0.0, 0.0, std::numbers::pi / 2}, 0.0, t);
  t += 100'000;
  const Pose2 p = f.update(Pose2{0.0, 1.0, std::numbers::pi / 2}, 0.0, t);
  CHECK(p.x_m == doctest::Approx(1.0).epsilon(0.01));
  CHECK(std::fabs(p.y_m) < 0.01);
  // Backing up 0.5 m.
  t += 100'000;
  const Pose2 q = f.update(Pose2{0.0, 0.5, std::numbers::pi / 2}, 0.0, t);
  CHECK(q.x_m == doctest::Approx(0.5).epsilon(0.02));
}

TEST_CASE("without a gyro the odometry is followed; the gyro re-enters without a jump") {
  HeadingFuser f;
  std::int64_t t = 0;
  f.update(Pose2{}, 0.0, t);
  t += 100'000;
  f.update(Pose2{0.0, 0.0, 0.3}, std::nullopt, t);
  CHECK(f.pose().theta_rad == doctest::Approx(0.3));
  CHECK(f.last_gyro_weight() == 0.0);
  t += 100'000;
  f.update(Pose2{0.0, 0.0, 0.3}, 5.0, t);  // gyro back with an unrelated absolute value
  CHECK(f.pose().theta_rad == doctest::Approx(0.3));
  t += 100'000;
  f.update(Pose2{0.0, 0.0, 0.45}, 5.1, t);  // turning: gyro says 0.1, odometry 0.15
  CHECK(f.pose().theta_rad == doctest::Approx(0.4).epsilon(0.01));
  t += 100'000;
  f.update(Pose2{0.0, 0.0, 0.45}, std::nan(""), t);  // NaN is "no gyro"
  CHECK(f.pose().theta_rad == doctest::Approx(0.4).epsilon(0.01));
}
