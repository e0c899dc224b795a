// Sonar ray casting: each of the 16 transducers sees a wall placed across its
// beam at a known distance; nothing in range reads the maximum.

#include <doctest/doctest.h>

#include <cmath>

#include "p3at/sim/p3at_model.hpp"
#include "sim_test_util.hpp"

using namespace p3at::sim;
using p3at::sim::test::exact_robot;
using p3at::sim::test::kDeg;
using p3at::sim::test::world_of;

namespace {

// A 0.4 m wall across sonar `i`'s beam, `distance_m` from the transducer, for a robot at `pose`.
Segment wall_across_beam(const Pose& pose, int i, double distance_m) {
  const SonarPose& s = kP3atSonars[static_cast<std::size_t>(i)];
  const Vec2 origin = to_world(pose, {s.x_m, s.y_m});
  const double heading = pose.theta_rad + s.heading_deg * kDeg;
  const Vec2 centre{origin.x + distance_m * std::cos(heading), origin.y + distance_m * std::sin(heading)};
  const Vec2 across{-std::sin(heading) * 0.2, std::cos(heading) * 0.2};
  return {{centre.x - across.x, centre.y - across.y}, {centre.x + across.x, centre.y + across.y}};
}

}  // namespace

TEST_CASE("every sonar reads the distance to a wall across its beam") {
  for (const double theta_deg : {0.0, 37.0, -120.0}) {
    const Pose pose{1.0, -2.0, theta_deg * kDeg};
    for (int i = 0; i < kP3atSonarCount; ++i) {
      CAPTURE(theta_deg);
      CAPTURE(i);
      World world(world_of({exact_robot("r", pose.x_m, pose.y_m, theta_deg)}, {wall_across_beam(pose, i, 1.7)}));
      world.step();
      CHECK(world.robot(0).sonar_ranges_m()[static_cast<std::size_t>(i)] == doctest::Approx(1.7).epsilon(1e-9));
    }
  }
}

TEST_CASE("a sonar that meets nothing within range reads the maximum range") {
  World open(world_of({exact_robot()}));
  open.step();
  for (double r : open.robot(0).sonar_ranges_m()) CHECK(r == doctest::Approx(5.0));

  const Pose pose{};
  World far(world_of({exact_robot()}, {wall_across_beam(pose, 3, 5.5)}));
  far.step();
  CHECK(far.robot(0).sonar_ranges_m()[3] == doctest::Approx(5.0));

  RobotConfig short_range = exact_robot();
  short_range.sonar.max_range_m = 1.0;
  World near(world_of({short_range}, {wall_across_beam(pose, 3, 1.5)}));
  near.step();
  CHECK(near.robot(0).sonar_ranges_m()[3] == doctest::Approx(1.0));
}

TEST_CASE("sonar noise is Gaussian around the true range") {
  RobotConfig r = exact_robot();
  r.sonar.noise_sd_m = 0.05;
  World world(world_of({r}, {wall_across_beam(Pose{}, 3, 2.0)}));
  double sum = 0.0;
  double sum_sq = 0.0;
  constexpr int n = 2000;
  for (int k = 0; k < n; ++k) {
    world.step();
    const double x = world.robot(0).sonar_ranges_m()[3] - 2.0;
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum_sq / n - mean * mean);
  CHECK(std::abs(mean) < 0.005);
  CHECK(sd == doctest::Approx(0.05).epsilon(0.08));
}

TEST_CASE("a robot sees another robot with its sonar") {
  // robot b ahead and a little to the left, where sonar 3's beam (10°) meets
  // its rear edge (x = 3.0 - 0.313, y = 0.45 ± 0.2525).
  World world(world_of({exact_robot("a", 0.0, 0.0, 0.0), exact_robot("b", 3.0, 0.45, 0.0)}));
  world.step();
  const double front = 3.0 - kP3atLengthM / 2.0;
  const SonarPose& s3 = kP3atSonars[3];
  const double expected = (front - s3.x_m) / std::cos(s3.heading_deg * kDeg);
  REQUIRE(std::abs(s3.y_m + (front - s3.x_m) * std::tan(s3.heading_deg * kDeg) - 0.45) < 0.25);
  CHECK(world.robot(0).sonar_ranges_m()[3] == doctest::Approx(expected).epsilon(1e-9));
}
