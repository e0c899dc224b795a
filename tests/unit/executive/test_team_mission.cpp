// Whole missions in fast time: two RobotExecutives, fake drive bases and a fake
// team link wired together, cycled by the test as a simulator would (one cycle
// per robot per 100 ms of simulated time).

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "fake_clock.hpp"
#include "fake_drive_base.hpp"
#include "fake_team_link.hpp"
#include "mission_builder.hpp"
#include "p3at/common/log.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/mission/loader.hpp"

namespace mission = p3at::mission;
using doctest::Approx;
using p3at::exec::Phase;
using p3at::exec::RobotExecutive;
using p3at::exec::TransitionEvent;
using p3at::test::FakeClock;
using p3at::test::FakeDriveBase;
using p3at::test::FakeTeamLink;
using p3at::test::RobotBuilder;

namespace {

/// The relay of examples/relay/mission.yaml, built in code.
mission::Mission relay() {
  RobotBuilder r1("robot1", {1.0, 1.0, 0.0});
  mission::GoToGuardedParams go1 = p3at::test::go_to(3.0, 1.0, 0.1);
  r1.state("drive", go1).state("tell", mission::NotifyParams{"r1_done"}).state("done", mission::StopParams{});
  r1.transition("drive", "tell", p3at::test::at_goal(3.0, 1.0, 0.2));
  r1.transition("tell", "done", mission::MessageSentParams{"r1_done"});
  RobotBuilder r2("robot2", {1.0, 2.0, 0.0});
  mission::GoToGuardedParams go2 = p3at::test::go_to(3.0, 2.0, 0.1);
  r2.state("wait", mission::StopParams{}).state("drive", go2).state("done", mission::StopParams{});
  r2.transition("wait", "drive", mission::NotifiedParams{"r1_done"});
  r2.transition("drive", "done", p3at::test::at_goal(3.0, 2.0, 0.2));
  return p3at::test::make_mission({r1.build(), r2.build()}, {mission::Message{"r1_done", 0, {1}}});
}

/// Two robots in lock-step fast time.
struct Team {
  Team(const mission::Mission& m, std::uint64_t seed)
      : d1(&clock), d2(&clock), l1(m.robots[0].name), l2(m.robots[1].name),
        e1(m, 0, d1, l1, clock, options(seed)), e2(m, 1, d2, l2, clock, options(seed)) {
    p3at::log::threshold() = std::getenv("P3AT_TEST_LOG") ? p3at::log::Level::info : p3at::log::Level::error;
    FakeTeamLink::connect(l1, l2);
  }
  p3at::exec::ExecutiveOptions options(std::uint64_t seed) {
    p3at::exec::ExecutiveOptions o;
    o.seed = seed;
    o.on_transition = [this](const TransitionEvent& e) { events.push_back(e); };
    return o;
  }
  /// Runs until both robots have finished or aborted; returns the cycles run.
  int run(int max_cycles = 3000) {
    int k = 0;
    while ((e1.running() || e2.running()) && k < max_cycles) {
      clock.advance_us(100'000);
      d1.step();
      d2.step();
      e1.cycle();
      e2.cycle();
      ++k;
    }
    return k;
  }
  FakeClock clock;
  FakeDriveBase d1, d2;
  FakeTeamLink l1, l2;
  std::vector<TransitionEvent> events;
  RobotExecutive e1, e2;
};

void check_relay_run(Team& team) {
  const int cycles = team.run();
  CHECK(cycles < 3000);
  REQUIRE(team.e1.outcome().phase == Phase::finished);
  REQUIRE(team.e2.outcome().phase == Phase::finished);
  CHECK(team.e1.state_name() == "done");
  CHECK(team.e2.state_name() == "done");
  // Perfect odometry: the believed pose is the true pose, within the AtGoal radius.
  const auto goal_of = [](const RobotExecutive& e) {
    return std::get<mission::GoToGuardedParams>(e.robot().states[*e.robot().find_state("drive")].behavior).goal;
  };
  CHECK(std::hypot(team.e1.pose().x_m - goal_of(team.e1).x_m, team.e1.pose().y_m - goal_of(team.e1).y_m) <= 0.2);
  CHECK(std::hypot(team.e2.pose().x_m - goal_of(team.e2).x_m, team.e2.pose().y_m - goal_of(team.e2).y_m) <= 0.2);
  // The order of events: r1 arrives, r1's message is acknowledged, r2 starts, r2 arrives.
  REQUIRE(team.events.size() == 4);
  CHECK(team.events[0].robot == 0);
  CHECK(team.events[0].cause == mission::TriggerKind::at_goal);
  // r1's notification goes out on entering "tell"; r2 receives it on its next
  // poll, in the same cycle (robots are cycled in order), and starts.
  CHECK(team.events[1].robot == 1);
  CHECK(team.events[1].cause == mission::TriggerKind::notified);
  CHECK(team.events[1].t_s == Approx(team.events[0].t_s));
  CHECK(team.events[2].robot == 0);
  CHECK(team.events[2].cause == mission::TriggerKind::message_sent);
  CHECK(team.events[2].t_s == Approx(team.events[0].t_s + 0.1));
  CHECK(team.events[3].robot == 1);
  CHECK(team.events[3].cause == mission::TriggerKind::at_goal);
  // robot2 held still until notified: it needed as long as robot1 to drive.
  CHECK(team.events[3].t_s - team.events[1].t_s > 0.7 * team.events[0].t_s);
  CHECK(team.l1.notify_calls.size() == 1);
  CHECK(team.l2.teammate_status().back().phase == "finished");
  CHECK(team.e1.team_settled());
  CHECK(team.e2.team_settled());
}

}  // namespace

TEST_CASE("two-robot relay in fast time runs to completion") {
  Team team(relay(), 1);
  check_relay_run(team);
}

TEST_CASE("the example relay mission file runs to completion") {
  const mission::Mission m = mission::load_mission_file(std::string(P3AT_EXAMPLES_DIR) + "/relay/mission.yaml");
  Team team(m, 1);
  check_relay_run(team);
}

TEST_CASE("fast-time runs are deterministic for a seed and differ between seeds") {
  Team a(relay(), 7), b(relay(), 7), c(relay(), 8);
  a.run();
  b.run();
  c.run();
  REQUIRE(a.events.size() == 4);
  REQUIRE(b.events.size() == 4);
  CHECK(a.events.back().t_s == b.events.back().t_s);
  CHECK(a.e1.pose().x_m == b.e1.pose().x_m);
  CHECK(a.e2.pose().y_m == b.e2.pose().y_m);
  // The noise schema makes different seeds take different paths.
  CHECK((a.e1.pose().x_m != c.e1.pose().x_m || a.e1.pose().y_m != c.e1.pose().y_m));
}

TEST_CASE("one robot's link loss aborts both") {
  Team team(relay(), 3);
  for (int k = 0; k < 20; ++k) {
    team.clock.advance_us(100'000);
    team.d1.step();
    team.d2.step();
    team.e1.cycle();
    team.e2.cycle();
  }
  team.d1.set_link(p3at::hal::LinkState::link_lost, "no SIP for 1000 ms");
  team.run(10);
  CHECK(team.e1.outcome().phase == Phase::aborted);
  CHECK(team.e2.outcome().phase == Phase::aborted);
  CHECK(team.e2.outcome().reason.find("teammate robot1 aborted") == 0);
  CHECK(team.d2.stop_calls == 1);
}
