// The fast-time calling contract against the real in-process simulator
// (sim::World + sim::SimDriveBase, with sonar and odometry errors): per cycle,
// every robot's wait_for_update() (the first steps the world), then every
// robot's cycle(). The relay runs to completion and the same seed repeats it.

#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <string>

#include "fake_team_link.hpp"
#include "mission_builder.hpp"
#include "p3at/common/log.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/sim/sim_drive_base.hpp"
#include "p3at/sim/world.hpp"
#include "p3at/sim/world_config.hpp"

namespace mission = p3at::mission;
using p3at::exec::Phase;
using p3at::exec::RobotExecutive;
using p3at::test::FakeTeamLink;
using p3at::test::RobotBuilder;

namespace {

constexpr const char* kWorld = R"(
robots:
  - {name: robot1, x_m: 1.0, y_m: 1.0, theta_deg: 0}
  - {name: robot2, x_m: 1.0, y_m: 2.0, theta_deg: 0}
)";

mission::Mission relay() {
  // A 0.5 m sphere: with the default 1 m, robot2 parks in equilibrium between
  // the pull of its goal (ramped down inside the dropoff) and the push of
  // robot1's body, 0.3 m from its goal (see docs/executive.md).
  mission::GoToGuardedParams go1 = p3at::test::go_to(3.0, 1.0, 0.1);
  go1.sphere_m = 0.5;
  mission::GoToGuardedParams go2 = p3at::test::go_to(3.0, 2.0, 0.1);
  go2.sphere_m = 0.5;
  RobotBuilder r1("robot1", {1.0, 1.0, 0.0});
  r1.state("drive", go1).state("tell", mission::NotifyParams{"r1_done"}).state("done", mission::StopParams{});
  r1.transition("drive", "tell", p3at::test::at_goal(3.0, 1.0, 0.2));
  r1.transition("tell", "done", mission::MessageSentParams{"r1_done"});
  RobotBuilder r2("robot2", {1.0, 2.0, 0.0});
  r2.state("wait", mission::StopParams{}).state("drive", go2).state("done", mission::StopParams{});
  r2.transition("wait", "drive", mission::NotifiedParams{"r1_done"});
  r2.transition("drive", "done", p3at::test::at_goal(3.0, 2.0, 0.2));
  return p3at::test::make_mission({r1.build(), r2.build()}, {mission::Message{"r1_done", 0, {1}}});
}

struct Run {
  double t1_s = 0, t2_s = 0;
  double true_x2_m = 0, true_y2_m = 0;
};

Run run_relay(std::uint64_t seed) {
  p3at::log::threshold() = p3at::log::Level::error;
  const mission::Mission m = relay();
  p3at::sim::World world(p3at::sim::parse_world(kWorld, "inline"), seed);
  p3at::sim::SimDriveBase d1(world, 0), d2(world, 1);
  FakeTeamLink l1("robot1"), l2("robot2");
  FakeTeamLink::connect(l1, l2);
  p3at::exec::ExecutiveOptions options;
  options.seed = seed;
  RobotExecutive e1(m, 0, d1, l1, world.clock(), options);
  RobotExecutive e2(m, 1, d2, l2, world.clock(), options);
  for (int k = 0; k < 3000 && (e1.running() || e2.running()); ++k) {
    REQUIRE(d1.wait_for_update(150).ok());
    REQUIRE(d2.wait_for_update(150).ok());
    e1.cycle();
    e2.cycle();
  }
  CHECK(e1.outcome().phase == Phase::finished);
  CHECK(e2.outcome().phase == Phase::finished);
  CHECK(e1.stats().missed_updates() == 0);
  CHECK(e2.stats().missed_updates() == 0);
  const auto& truth = world.robot(1).true_pose();
  return Run{e1.elapsed_s(), e2.elapsed_s(), truth.x_m, truth.y_m};
}

}  // namespace

TEST_CASE("fast time with the simulator: the relay completes, and a seed repeats it exactly") {
  const Run a = run_relay(5);
  const Run b = run_relay(5);
  CHECK(a.t1_s > 5.0);
  CHECK(a.t2_s > a.t1_s);
  // True position: odometry errors leave it near, not exactly at, the goal.
  CHECK(std::hypot(a.true_x2_m - 3.0, a.true_y2_m - 2.0) < 0.6);
  CHECK(a.t2_s == b.t2_s);
  CHECK(a.true_x2_m == b.true_x2_m);
  CHECK(a.true_y2_m == b.true_y2_m);
}
