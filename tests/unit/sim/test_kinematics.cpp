// P3-AT kinematics: acceleration limits, velocity targets, heading and move
// controllers, and motor enable.

#include <doctest/doctest.h>

#include "sim_test_util.hpp"

using namespace p3at::sim;
using p3at::sim::test::exact_robot;
using p3at::sim::test::kDeg;
using p3at::sim::test::run_for;
using p3at::sim::test::world_of;

TEST_CASE("translational velocity ramps at the acceleration limit and reaches the target") {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_trans_vel(0.6);
  world.step();  // 0.1 s at 0.3 m/s²
  CHECK(c.trans_vel_mps() == doctest::Approx(0.03).epsilon(1e-6));
  CHECK(world.robot(0).true_trans_vel_mps() == doctest::Approx(0.03).epsilon(1e-6));
  run_for(world, 0.9);
  CHECK(c.trans_vel_mps() == doctest::Approx(0.3).epsilon(1e-6));
  run_for(world, 1.0);
  CHECK(c.trans_vel_mps() == doctest::Approx(0.6).epsilon(1e-6));
  run_for(world, 1.0);
  CHECK(c.trans_vel_mps() == doctest::Approx(0.6).epsilon(1e-6));  // held, never above

  SUBCASE("stop decelerates at 0.6 m/s²") {
    c.stop();
    run_for(world, 0.5);
    CHECK(c.trans_vel_mps() == doctest::Approx(0.3).epsilon(1e-6));
    run_for(world, 0.5);
    CHECK(c.trans_vel_mps() == doctest::Approx(0.0));
    CHECK_FALSE(world.robot(0).moving());
  }
  SUBCASE("commands above the maximum are clamped") {
    c.set_max_trans_vel(0.4);
    c.command_trans_vel(5.0);
    run_for(world, 1.0);
    CHECK(c.trans_vel_mps() == doctest::Approx(0.4).epsilon(1e-6));
  }
}

TEST_CASE("SETA changes acceleration and negative SETA changes deceleration") {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.set_trans_accel(0.1);
  c.set_trans_accel(-0.2);
  c.command_trans_vel(0.3);
  run_for(world, 1.0);
  CHECK(c.trans_vel_mps() == doctest::Approx(0.1).epsilon(1e-6));
  c.stop();
  run_for(world, 0.2);
  CHECK(c.trans_vel_mps() == doctest::Approx(0.06).epsilon(1e-6));
}

TEST_CASE("rotational velocity ramps at 100 deg/s² and turns the robot") {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_rot_vel(30 * kDeg);
  world.step();
  CHECK(c.rot_vel_radps() == doctest::Approx(10 * kDeg).epsilon(1e-6));
  run_for(world, 0.2);
  CHECK(c.rot_vel_radps() == doctest::Approx(30 * kDeg).epsilon(1e-6));
  run_for(world, 1.0);
  // Turning in place: no translation, heading grew.
  CHECK(world.robot(0).true_pose().x_m == doctest::Approx(0.0));
  CHECK(world.robot(0).true_pose().theta_rad > 30 * kDeg);
  CHECK(world.robot(0).true_rot_vel_radps() == doctest::Approx(30 * kDeg).epsilon(1e-6));
}

TEST_CASE("drive 1 m at 0.3 m/s without errors: odometry and truth agree on 1 m") {
  World world(world_of({exact_robot("r", 2.0, 3.0, 0.0)}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.set_max_trans_vel(0.3);
  c.command_move(1.0, world.robot(0).odometry_distance_m());
  run_for(world, 2.0);
  CHECK(c.trans_vel_mps() == doctest::Approx(0.3).epsilon(1e-6));  // cruising at the set maximum
  run_for(world, 4.0);
  const Pose& t = world.robot(0).true_pose();
  CHECK(t.x_m == doctest::Approx(3.0).epsilon(0.002));
  CHECK(t.y_m == doctest::Approx(3.0));
  CHECK(world.robot(0).odometry().x_m == doctest::Approx(1.0).epsilon(0.003));
  CHECK(world.robot(0).odometry().x_m == doctest::Approx(t.x_m - 2.0).epsilon(1e-9));
  CHECK_FALSE(world.robot(0).moving());
}

TEST_CASE("heading controller turns to absolute headings, negative ones included") {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_heading(90 * kDeg);
  run_for(world, 5.0);
  CHECK(world.robot(0).odometry().theta_rad == doctest::Approx(90 * kDeg).epsilon(0.005));
  CHECK(world.robot(0).true_pose().theta_rad == doctest::Approx(90 * kDeg).epsilon(0.005));
  c.command_heading(-90 * kDeg);
  run_for(world, 8.0);
  CHECK(world.robot(0).odometry().theta_rad == doctest::Approx(-90 * kDeg).epsilon(0.005));
  CHECK_FALSE(world.robot(0).moving());
}

TEST_CASE("disabled motors do not move the robot") {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.command_trans_vel(0.3);
  c.command_rot_vel(0.3);
  run_for(world, 2.0);
  CHECK(world.robot(0).true_pose().x_m == doctest::Approx(0.0));
  CHECK(world.robot(0).true_pose().theta_rad == doctest::Approx(0.0));
  CHECK_FALSE(world.robot(0).moving());

  c.enable_motors(true);
  c.command_trans_vel(0.3);
  run_for(world, 1.0);
  CHECK(world.robot(0).moving());
  c.enable_motors(false);  // halts at once
  world.step();
  CHECK_FALSE(world.robot(0).moving());
}

TEST_CASE("emergency stop halts at once and needs re-enabling") {
  World world(world_of({exact_robot()}));
  MotionController& c = world.robot(0).controller();
  c.enable_motors(true);
  c.command_trans_vel(0.3);
  run_for(world, 2.0);
  c.emergency_stop();
  CHECK(c.estop());
  CHECK_FALSE(c.motors_enabled());
  const double x = world.robot(0).true_pose().x_m;
  world.step();
  CHECK(world.robot(0).true_pose().x_m == doctest::Approx(x));
  c.enable_motors(true);
  CHECK_FALSE(c.estop());
}
