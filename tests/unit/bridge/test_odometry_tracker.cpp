#include <doctest/doctest.h>

#include <cmath>

#include "p3at/bridge/odometry_tracker.hpp"

using namespace p3at;

TEST_CASE("odometry starts at zero and follows differences") {
  bridge::OdometryTracker t(arcos::RobotParams::for_subclass("p3at-sh"));
  t.update(1000, 2000, 0);
  CHECK(t.pose().x_m == 0.0);
  t.update(1500, 2000, 0);
  CHECK(t.pose().x_m == doctest::Approx(0.5));
  CHECK(t.pose().y_m == doctest::Approx(0.0));
}

TEST_CASE("X wraps forward and backward through the 15-bit counter") {
  bridge::OdometryTracker t(arcos::RobotParams::for_subclass("p3at-sh"));
  t.update(0x7FF0, 0, 0);
  t.update(0x0010, 0, 0);  // +0x20 through the wrap
  CHECK(t.pose().x_m == doctest::Approx(0.032));
  t.update(0x7FE0, 0, 0);  // -0x30 back through it
  CHECK(t.pose().x_m == doctest::Approx(-0.016));
}

TEST_CASE("the first SIP's heading is our zero; displacement is rotated into our frame") {
  bridge::OdometryTracker t(arcos::RobotParams::for_subclass("p3at-sh"));
  t.update(100, 100, 1024);   // firmware heading +90°
  t.update(100, 1100, 1024);  // moved +1 m along the firmware's Y = straight ahead
  CHECK(t.pose().x_m == doctest::Approx(1.0));
  CHECK(std::fabs(t.pose().y_m) < 1e-9);
  CHECK(t.pose().theta_rad == doctest::Approx(0.0));
}

TEST_CASE("heading is continuous through many turns") {
  bridge::OdometryTracker t(arcos::RobotParams::for_subclass("p3at-sh"));
  std::int16_t th = 0;
  t.update(0, 0, th);
  for (int i = 0; i < 40; ++i) {  // 40 × 100 units = 4000 units ≈ 351.6°; do it 3 times
    th = static_cast<std::int16_t>((th + 100 + 2048) % 4096 - 2048);
    t.update(0, 0, th);
  }
  CHECK(t.pose().theta_rad == doctest::Approx(4000 * 2 * 3.14159265358979323846 / 4096));
}

TEST_CASE("after a rebaseline (reconnect) the pose continues where it was") {
  bridge::OdometryTracker t(arcos::RobotParams::for_subclass("p3at-sh"));
  t.update(0, 0, 0);
  t.update(1000, 0, 0);
  t.rebaseline();
  t.update(5000, 5000, 0);  // the controller restarted its counters elsewhere
  CHECK(t.pose().x_m == doctest::Approx(1.0));
  t.update(5500, 5000, 0);
  CHECK(t.pose().x_m == doctest::Approx(1.5));
}
