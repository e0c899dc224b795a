// The odometry error model: systematic encoder-scale and track-width errors
// give the expected bias; random errors grow in variance as drawn per update;
// the same seed gives the same run.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "p3at/sim/p3at_model.hpp"
#include "sim_test_util.hpp"

using namespace p3at::sim;
using p3at::sim::test::exact_robot;
using p3at::sim::test::kDeg;
using p3at::sim::test::run_for;
using p3at::sim::test::world_of;

TEST_CASE("a left encoder that over-reports makes the robot curve left while odometry says straight") {
  RobotConfig r = exact_robot();
  r.odometry.left_scale = 1.02;
  World world(world_of({r}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_trans_vel(0.3);
  run_for(world, 10.0);
  const SimRobot& robot = world.robot(0);
  CHECK(robot.odometry().theta_rad == doctest::Approx(0.0));
  CHECK(robot.odometry().y_m == doctest::Approx(0.0));
  // Encoders report equal wheel travel d; the left wheel really went d/1.02.
  const double d = robot.odometry_distance_m();
  const double expected_heading = d * (1.0 - 1.0 / 1.02) / kNominalTrackM;
  CHECK(robot.true_pose().theta_rad == doctest::Approx(expected_heading).epsilon(1e-6));
  CHECK(robot.true_pose().theta_rad > 0.05);  // a visible left curve, not a rounding effect
  // Distance along the arc is the mean of the two true wheel distances.
  const double arc = d * (1.0 + 1.0 / 1.02) / 2.0;
  const double radius = arc / expected_heading;
  CHECK(robot.true_pose().x_m == doctest::Approx(radius * std::sin(expected_heading)).epsilon(1e-4));
}

TEST_CASE("an effective track wider than nominal makes the robot turn less than odometry says") {
  RobotConfig r = exact_robot();
  r.odometry.track_ratio = 1.1;
  World world(world_of({r}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_heading(90 * kDeg);
  run_for(world, 6.0);
  CHECK(world.robot(0).odometry().theta_rad == doctest::Approx(90 * kDeg).epsilon(0.005));
  CHECK(world.robot(0).true_pose().theta_rad ==
        doctest::Approx(world.robot(0).odometry().theta_rad / 1.1).epsilon(1e-9));
}

namespace {

struct RunResult {
  double error_at_5s = 0.0;
  double error_at_10s = 0.0;
};

// Odometric minus true distance after 5 s and 10 s of VEL 0.3.
RunResult drive_straight(std::uint64_t seed, double sd) {
  RobotConfig r = exact_robot();
  r.odometry.random_trans_per_unit = sd;
  World world(world_of({r}), seed);
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_trans_vel(0.3);
  RunResult out;
  run_for(world, 5.0);
  out.error_at_5s = world.robot(0).odometry().x_m - world.robot(0).true_pose().x_m;
  run_for(world, 5.0);
  out.error_at_10s = world.robot(0).odometry().x_m - world.robot(0).true_pose().x_m;
  return out;
}

double sum_of_squared_cycle_distances(double seconds) {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_trans_vel(0.3);
  double sum = 0.0;
  for (int i = 0; i < static_cast<int>(seconds * 10.0 + 0.5); ++i) {
    const double before = world.robot(0).true_pose().x_m;
    world.step();
    const double d = world.robot(0).true_pose().x_m - before;
    sum += d * d;
  }
  return sum;
}

double variance(const std::vector<double>& xs) {
  double mean = 0.0;
  for (double x : xs) mean += x;
  mean /= static_cast<double>(xs.size());
  double v = 0.0;
  for (double x : xs) v += (x - mean) * (x - mean);
  return v / static_cast<double>(xs.size() - 1);
}

}  // namespace

TEST_CASE("random odometry error: one draw per update, variance grows with the updates") {
  constexpr double sd = 0.02;
  constexpr int runs = 400;
  std::vector<double> e5;
  std::vector<double> e10;
  for (int seed = 1; seed <= runs; ++seed) {
    const RunResult r = drive_straight(static_cast<std::uint64_t>(seed), sd);
    e5.push_back(r.error_at_5s);
    e10.push_back(r.error_at_10s);
  }
  // Each 100 ms update's distance d_i is scaled by (1 + N(0, sd²)):
  // Var(error) = sd² × Σ d_i². 400 runs estimate a variance within about ±7 % (1σ).
  const double expected5 = sd * sd * sum_of_squared_cycle_distances(5.0);
  const double expected10 = sd * sd * sum_of_squared_cycle_distances(10.0);
  CHECK(variance(e5) == doctest::Approx(expected5).epsilon(0.25));
  CHECK(variance(e10) == doctest::Approx(expected10).epsilon(0.25));
  CHECK(variance(e10) > 1.5 * variance(e5));
}

TEST_CASE("same seed, same run; another seed, another run") {
  const auto run = [](std::uint64_t seed) {
    RobotConfig r = exact_robot();
    r.odometry.random_trans_per_unit = 0.01;
    r.odometry.random_rot_per_unit = 0.01;
    r.sonar.noise_sd_m = 0.02;
    World world(world_of({r}, {{{3.0, -5.0}, {3.0, 5.0}}}), seed);
    MotionController& c = world.robot(0).controller();
    c.enable_motors(true);
    c.command_trans_vel(0.2);
    c.command_rot_vel(0.1);
    run_for(world, 5.0);
    return std::vector<double>{world.robot(0).odometry().x_m, world.robot(0).odometry().y_m,
                               world.robot(0).odometry().theta_rad, world.robot(0).sonar_ranges_m()[3]};
  };
  CHECK(run(42) == run(42));
  CHECK(run(42) != run(43));
}
