// The fast-time gyro (the P3-AT firmware's gyro correction): with a `gyro:`
// block the odometric heading integrates the gyro's measured rate (bias,
// drift, noise, scale error) instead of the wheel-derived rotation; without
// one nothing changes.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "p3at/sim/sim_drive_base.hpp"
#include "sim_test_util.hpp"

using namespace p3at::sim;
using p3at::sim::test::exact_robot;
using p3at::sim::test::kDeg;
using p3at::sim::test::run_for;
using p3at::sim::test::world_of;

namespace {

RobotConfig with_gyro(RobotConfig r, GyroModel g) {
  r.gyro = g;
  return r;
}

bool same_pose(const Pose& a, const Pose& b) { return a.x_m == b.x_m && a.y_m == b.y_m && a.theta_rad == b.theta_rad; }

}  // namespace

TEST_CASE("a gyro makes a robot with a large track error turn correctly, apart from the gyro's drift") {
  RobotConfig r = exact_robot();
  r.odometry.track_ratio = 1.3;  // the wheels say 30 % more turn than the robot makes
  const double bias_degps = 0.1;
  for (const bool gyro : {false, true}) {
    CAPTURE(gyro);
    World world(world_of({gyro ? with_gyro(r, GyroModel{bias_degps, 0.0, 0.0, 0.0}) : r}));
    MotionController& c = world.robot(0).controller();
    c.enable_motors(true);
    c.command_heading(90 * kDeg);
    run_for(world, 10.0);
    const SimRobot& robot = world.robot(0);
    CHECK(robot.odometry().theta_rad == doctest::Approx(90 * kDeg).epsilon(0.005));  // reached, as it believes
    if (!gyro) {
      CHECK(robot.true_pose().theta_rad == doctest::Approx(90 * kDeg / 1.3).epsilon(0.005));  // about 69°
    } else {
      // The gyro heading is the true heading plus the bias integrated since power-up.
      const double drift_rad = bias_degps * kDeg * 10.0;
      CHECK(robot.true_pose().theta_rad == doctest::Approx(robot.odometry().theta_rad - drift_rad).epsilon(1e-9));
      CHECK(std::abs(robot.true_pose().theta_rad - 90 * kDeg) < 1.3 * kDeg);  // 1° of drift, 0.2° of tolerance
    }
  }
}

TEST_CASE("at rest a gyro heading drifts by bias and drift, the robot does not move, and SimDriveBase reports it") {
  const double bias_degps = 0.05;
  const double drift_degps_per_s = 0.002;
  World world(world_of({with_gyro(exact_robot(), GyroModel{bias_degps, drift_degps_per_s, 0.0, 0.0})}));
  SimDriveBase drive(world, 0);
  for (int i = 0; i < 600; ++i) REQUIRE(drive.wait_for_update(1000).value());
  // 6000 samples of 10 ms at t_k = k · 10 ms: Σ (b + d · t_k) · dt = b·T + d·(T² + T·dt)/2.
  const double t = 60.0;
  const double dt = 0.01;
  const double expected = (bias_degps * t + drift_degps_per_s * (t * t + t * dt) / 2.0) * kDeg;
  const SimRobot& robot = world.robot(0);
  CHECK(robot.odometry().theta_rad == doctest::Approx(expected).epsilon(1e-9));
  CHECK(expected > 6.5 * kDeg);  // 3° of bias and 3.6° of drift: not a rounding effect
  CHECK(same_pose(robot.true_pose(), Pose{}));
  CHECK(robot.odometry().x_m == 0.0);
  CHECK(std::abs(drive.state().odometry.theta_rad - expected) <= 2.0 * 3.14159265358979 / 4096.0);
}

TEST_CASE("the gyro's noise makes the heading a random walk of sd noise · sqrt(dt · t)") {
  const double noise_degps = 1.0;
  const double seconds = 25.0;
  std::vector<double> headings;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    World world(world_of({with_gyro(exact_robot(), GyroModel{0.0, 0.0, noise_degps, 0.0})}), seed);
    run_for(world, seconds);
    headings.push_back(world.robot(0).odometry().theta_rad / kDeg);
    CHECK(same_pose(world.robot(0).true_pose(), Pose{}));
  }
  double mean = 0.0;
  for (double h : headings) mean += h;
  mean /= static_cast<double>(headings.size());
  double var = 0.0;
  for (double h : headings) var += (h - mean) * (h - mean);
  const double sd = std::sqrt(var / static_cast<double>(headings.size() - 1));
  const double expected_sd = noise_degps * std::sqrt(0.01 * seconds);  // 0.5°
  // 300 samples: the sd's standard error is about 4 %, the mean's 0.03°.
  CHECK(sd == doctest::Approx(expected_sd).epsilon(0.12));
  CHECK(std::abs(mean) < 3.0 * expected_sd / std::sqrt(300.0));
}

TEST_CASE("a gyro's scale error scales the odometric turn") {
  World world(world_of({with_gyro(exact_robot(), GyroModel{0.0, 0.0, 0.0, 0.02})}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_rot_vel(0.5);
  run_for(world, 4.0);  // about 1.75 rad: no wrap
  const SimRobot& robot = world.robot(0);
  CHECK(robot.true_pose().theta_rad > 1.5);
  CHECK(robot.odometry().theta_rad == doctest::Approx(1.02 * robot.true_pose().theta_rad).epsilon(1e-9));
}

TEST_CASE("the odometric position follows the gyro heading: a drifting gyro bends a straight path") {
  const double bias_degps = 0.5;
  World world(world_of({with_gyro(exact_robot(), GyroModel{bias_degps, 0.0, 0.0, 0.0})}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_trans_vel(0.3);
  run_for(world, 20.0);
  const SimRobot& robot = world.robot(0);
  CHECK(robot.true_pose().y_m == 0.0);  // really straight
  CHECK(robot.true_pose().theta_rad == 0.0);
  // Believed: heading b·t, so y = ∫ v sin(b t) dt ≈ b ∫ v t dt over the drive.
  const double b = bias_degps * kDeg;
  double expected_y = 0.0;
  double v = 0.0;
  for (int k = 1; k <= 2000; ++k) {  // v ramps at 0.3 m/s² to 0.3 m/s, as the controller does
    v = std::min(0.3, v + 0.3 * 0.01);
    expected_y += v * 0.01 * std::sin(b * (k - 0.5) * 0.01);
  }
  CHECK(expected_y > 0.4);
  CHECK(robot.odometry().y_m == doctest::Approx(expected_y).epsilon(0.01));
  CHECK(robot.odometry().x_m == doctest::Approx(robot.true_pose().x_m).epsilon(0.01));
}

TEST_CASE("without a gyro block nothing changes, and a gyro draws from a stream of its own") {
  // Random odometry errors and sonar noise on, walls to echo from, turning.
  RobotConfig a = exact_robot("a", 2.0, 2.0);
  RobotConfig b = exact_robot("b", 2.0, 8.0);
  for (RobotConfig* r : {&a, &b}) {
    r->odometry.random_trans_per_unit = 0.02;
    r->odometry.random_rot_per_unit = 0.03;
    r->sonar.noise_sd_m = 0.01;
  }
  const std::vector<Segment> walls{{{0, 0}, {20, 0}}, {{0, 10}, {20, 10}}, {{0, 0}, {0, 10}}};
  World plain(world_of({a, b}, walls), 5);
  World gyro(world_of({a, with_gyro(b, GyroModel{0.3, 0.01, 0.5, 0.01})}, walls), 5);
  for (World* w : {&plain, &gyro}) {
    for (std::size_t i = 0; i < 2; ++i) {
      w->robot(i).controller().enable_motors(true);
      w->robot(i).controller().command_trans_vel(0.4);
      w->robot(i).controller().command_rot_vel(0.1);
    }
  }
  for (int cycle = 0; cycle < 200; ++cycle) {
    plain.step();
    gyro.step();
    // Robot a, without a gyro in both worlds, runs bit for bit the same.
    REQUIRE(same_pose(plain.robot(0).true_pose(), gyro.robot(0).true_pose()));
    REQUIRE(same_pose(plain.robot(0).odometry(), gyro.robot(0).odometry()));
    REQUIRE(plain.robot(0).sonar_ranges_m() == gyro.robot(0).sonar_ranges_m());
    // Robot b really moves the same (velocity mode does not read the heading),
    // and its odometric distance and sonar draws are unchanged: only its
    // odometric heading, and the position integrated along it, differ.
    REQUIRE(same_pose(plain.robot(1).true_pose(), gyro.robot(1).true_pose()));
    REQUIRE(plain.robot(1).odometry_distance_m() == gyro.robot(1).odometry_distance_m());
    REQUIRE(plain.robot(1).sonar_ranges_m() == gyro.robot(1).sonar_ranges_m());
  }
  CHECK(plain.robot(1).odometry().theta_rad != gyro.robot(1).odometry().theta_rad);

  // enabled: false is the same as no block at all.
  const std::string with_block = "robots:\n  - {name: r, x_m: 0, y_m: 0, gyro: {enabled: false, bias_degps: 5}}\n";
  const std::string without = "robots:\n  - {name: r, x_m: 0, y_m: 0}\n";
  World off(parse_world(with_block, "w.yaml"), 3);
  World none(parse_world(without, "w.yaml"), 3);
  for (World* w : {&off, &none}) {
    w->robot(0).controller().enable_motors(true);
    w->robot(0).controller().command_heading(2.0);
    w->robot(0).controller().command_trans_vel(0.3);
  }
  run_for(off, 10.0);
  run_for(none, 10.0);
  CHECK(same_pose(off.robot(0).true_pose(), none.robot(0).true_pose()));
  CHECK(same_pose(off.robot(0).odometry(), none.robot(0).odometry()));
}
