// The in-process drive base: fast time on the SimClock, one world step per
// cycle shared by every robot, commands reaching the controller.

#include <doctest/doctest.h>


#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "p3at/sim/sim_drive_base.hpp"
#include "p3at/sim/truth_csv.hpp"
#include "sim_test_util.hpp"
#include "scratch.hpp"

using namespace p3at::sim;
using p3at::sim::test::exact_robot;
using p3at::sim::test::world_of;

TEST_CASE("two drive bases on one world step it once per cycle in lock-step") {
  World world(world_of({exact_robot("a", 0.0, 0.0), exact_robot("b", 0.0, 3.0)}));
  SimDriveBase a(world, 0);
  SimDriveBase b(world, 1);
  REQUIRE(a.set_velocity(0.3, 0.0).ok());
  REQUIRE(b.set_velocity(0.0, 0.2).ok());
  for (int cycle = 1; cycle <= 50; ++cycle) {
    auto ua = a.wait_for_update(1000);
    auto ub = b.wait_for_update(1000);
    REQUIRE(ua.ok());
    REQUIRE(ub.ok());
    CHECK(*ua);
    CHECK(*ub);
    CHECK(world.cycle_count() == static_cast<std::uint64_t>(cycle));
    CHECK(a.state().update_count == b.state().update_count);
  }
  CHECK(world.clock().now_us() == 5'000'000);
  CHECK(a.state().stamp_us == 5'000'000);
  CHECK(a.state().odometry.x_m > 1.0);
  CHECK(a.state().trans_vel_mps == doctest::Approx(0.3));
  CHECK(b.state().odometry.theta_rad > 0.5);
  CHECK(b.state().link == p3at::hal::LinkState::ok);
  CHECK(b.state().motors_enabled);
  CHECK(a.state().sonar_m[0] == doctest::Approx(5.0));
  CHECK(world.robot(0).controller().stats().motion_commands == 1);
}

TEST_CASE("a short timeout advances the clock without an update") {
  World world(world_of({exact_robot()}));
  SimDriveBase base(world, 0);
  auto got = base.wait_for_update(30);
  REQUIRE(got.ok());
  CHECK_FALSE(*got);
  CHECK(world.clock().now_us() == 30'000);
  CHECK(world.cycle_count() == 0);
  got = base.wait_for_update(100);
  REQUIRE(got.ok());
  CHECK(*got);
  CHECK(world.clock().now_us() == 100'000);
  CHECK(world.cycle_count() == 1);
}

TEST_CASE("emergency stop refuses motion until re-armed") {
  World world(world_of({exact_robot()}));
  SimDriveBase base(world, 0);
  REQUIRE(base.set_velocity(0.3, 0.0).ok());
  for (int i = 0; i < 10; ++i) REQUIRE(base.wait_for_update(200).ok());
  REQUIRE(base.emergency_stop().ok());
  CHECK(base.state().link == p3at::hal::LinkState::safety_stop);
  CHECK(base.state().estop_pressed);
  const auto refused = base.set_velocity(0.3, 0.0);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().code == p3at::Error::Code::state);
  REQUIRE(base.wait_for_update(200).ok());
  CHECK_FALSE(base.state().moving);
  base.rearm();
  CHECK(base.set_velocity(0.1, 0.0).ok());
  CHECK_FALSE(base.set_velocity(std::nan(""), 0.0).ok());
  REQUIRE(base.stop().ok());
}

TEST_CASE("odometry is quantised like the SIP counters of the subclass") {
  RobotConfig r = exact_robot();
  r.subclass = "p3at";
  World world(world_of({r}));
  SimDriveBase base(world, 0);
  REQUIRE(base.set_velocity(0.123, 0.0).ok());
  for (int i = 0; i < 23; ++i) REQUIRE(base.wait_for_update(200).ok());
  const double units = base.state().odometry.x_m * 1000.0 / 0.465;
  CHECK(units == doctest::Approx(std::round(units)).epsilon(1e-9));
  CHECK(base.state().odometry.x_m == doctest::Approx(world.robot(0).odometry().x_m).epsilon(0.001));
}

TEST_CASE("the truth CSV has a header and one row per robot per cycle") {
  World world(world_of({exact_robot("a", 1.0, 2.0, 90.0), exact_robot("b", 5.0, 2.0)}));
  const std::string path = p3at::test::scratch_path("truth.csv");
  auto writer = TruthCsvWriter::open(path);
  REQUIRE(writer.ok());
  world.robot(0).controller().enable_motors(true);
  world.robot(0).controller().command_trans_vel(0.3);
  for (int i = 0; i < 3; ++i) {
    world.step();
    REQUIRE((*writer)->write_cycle(world).ok());
  }
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  REQUIRE(lines.size() == 7);
  CHECK(lines[0] == truth_csv_header());
  CHECK(lines[5].rfind("0.3,a,", 0) == 0);
  CHECK(lines[6].rfind("0.3,b,5.000000,2.000000,", 0) == 0);
  // robot a started facing +Y: odometry x becomes world y.
  CHECK(lines[5] == truth_csv_row(world, 0));
  CHECK(world.robot(0).odometry_in_world().y_m == doctest::Approx(world.robot(0).true_pose().y_m));
  CHECK(world.robot(0).odometry_in_world().y_m > 2.0);
  std::remove(path.c_str());

  CHECK_FALSE(TruthCsvWriter::open("/nonexistent-dir/x.csv").ok());
}
