// RobotExecutive: the cycle, transitions, Notify / Notified / MessageSent,
// aborts, telemetry and statistics, against in-process fakes.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "fake_clock.hpp"
#include "fake_drive_base.hpp"
#include "fake_team_link.hpp"
#include "mission_builder.hpp"
#include "p3at/common/log.hpp"
#include "p3at/executive/noise.hpp"
#include "p3at/executive/robot_executive.hpp"

namespace mission = p3at::mission;
using doctest::Approx;
using p3at::exec::Phase;
using p3at::exec::RobotExecutive;
using p3at::test::FakeClock;
using p3at::test::FakeDriveBase;
using p3at::test::FakeTeamLink;
using p3at::test::RobotBuilder;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// One robot with fakes around it; tick() = one 100 ms cycle.
struct Rig {
  explicit Rig(const mission::Mission& m, std::size_t index = 0, p3at::exec::ExecutiveOptions options = {})
      : drive(&clock), link(m.robots.at(index).name), exec(m, index, drive, link, clock, std::move(options)) {
    p3at::log::threshold() = p3at::log::Level::error;
  }
  void tick() {
    clock.advance_us(100'000);
    drive.step();
    exec.cycle();
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }
  FakeClock clock;
  FakeDriveBase drive;
  FakeTeamLink link;
  RobotExecutive exec;
};

/// Gives `state` a way out that never fires in a test (so it is not a final state).
RobotBuilder& never_ending(RobotBuilder& r, const std::string& state) {
  r.state("unreachable", mission::StopParams{});
  r.transition(state, "unreachable", mission::HasTurnedParams{100000.0, 0.0});
  return r;
}

mission::Mission one_robot(const RobotBuilder& robot, std::vector<mission::Message> messages = {}) {
  return p3at::test::make_mission({robot.build()}, std::move(messages));
}

/// robot1 plus a passive robot2 (so messages have a recipient / a sender).
mission::Mission with_teammate(const RobotBuilder& robot, std::vector<mission::Message> messages) {
  RobotBuilder mate("robot2", {0, 5, 0});
  mate.state("idle", mission::StopParams{});
  return p3at::test::make_mission({robot.build(), mate.build()}, std::move(messages));
}

}  // namespace

TEST_CASE("a mission whose initial state is final finishes on the first cycle") {
  Rig rig(one_robot(RobotBuilder("robot1", {}).state("only", mission::StopParams{})));
  rig.tick();
  CHECK(rig.exec.outcome().phase == Phase::finished);
  CHECK(rig.drive.stop_calls == 1);
  CHECK(rig.drive.set_velocity_calls == 0);
}

TEST_CASE("construction rejects what it cannot run") {
  FakeClock clock;
  FakeDriveBase drive(&clock);
  FakeTeamLink link("robot1");
  const auto m = one_robot(RobotBuilder("robot1", {}).state("s", mission::StopParams{}));
  CHECK_THROWS_AS(RobotExecutive(m, 1, drive, link, clock), std::invalid_argument);
  auto no_states = m;
  no_states.robots[0].states.clear();
  CHECK_THROWS_AS(RobotExecutive(no_states, 0, drive, link, clock), std::invalid_argument);
  RobotBuilder waits("robot1", {});
  waits.state("a", mission::StopParams{}).state("b", mission::StopParams{});
  waits.transition("a", "b", mission::NotifiedParams{"undeclared"});
  CHECK_THROWS_AS(RobotExecutive(one_robot(waits), 0, drive, link, clock), std::invalid_argument);
}

TEST_CASE("GoToGuarded drives to the goal; AtGoal finishes the mission and stops the robot") {
  RobotBuilder r("robot1", {1.0, 1.0, 0.0});
  r.state("drive", p3at::test::go_to(3.0, 2.0)).state("done", mission::StopParams{});
  r.transition("drive", "done", p3at::test::at_goal(3.0, 2.0, 0.2));
  Rig rig(one_robot(r));
  rig.tick();
  CHECK(rig.exec.started());
  CHECK(rig.exec.state_name() == "drive");
  CHECK(rig.exec.last_command().rot_radps > 0.0);  // goal is up and to the left of +x
  int cycles = 1;
  while (rig.exec.running() && cycles < 400) {
    rig.tick();
    ++cycles;
  }
  CHECK(rig.exec.outcome().phase == Phase::finished);
  CHECK(rig.exec.state_name() == "done");
  CHECK(std::hypot(rig.exec.pose().x_m - 3.0, rig.exec.pose().y_m - 2.0) <= 0.2);
  CHECK(rig.drive.stop_calls >= 1);
  CHECK(rig.drive.trans_cmd_mps == 0.0);
  CHECK(rig.drive.emergency_stop_calls == 0);
  // ~2.24 m at 0.3 m/s with a ramp-down: between 7.5 s and 40 s.
  CHECK(rig.exec.elapsed_s() > 7.0);
  CHECK(rig.exec.elapsed_s() < 40.0);
  REQUIRE_FALSE(rig.link.status_sent.empty());
  CHECK(rig.link.status_sent.back().phase == "finished");
  CHECK(rig.link.status_sent.back().state == "done");
  // Finished: further cycles command nothing, and the elapsed time is frozen.
  const int calls = rig.drive.set_velocity_calls;
  const double t_end = rig.exec.elapsed_s();
  rig.ticks(5);
  CHECK(rig.drive.set_velocity_calls == calls);
  CHECK(rig.exec.elapsed_s() == t_end);
}

TEST_CASE("odometry is re-zeroed at mission start and expressed in the mission frame") {
  RobotBuilder r("robot1", {5.5, 5.0, 90.0});
  r.state("spin", mission::SpinParams{10.0});
  r.state("end", mission::StopParams{});
  r.transition("spin", "end", mission::HasTurnedParams{180.0, 0.0});
  Rig rig(one_robot(r));
  // The base's odometry frame is elsewhere (a bridge that had been running).
  rig.drive.set_odometry_origin(p3at::hal::Pose2{10.0, -3.0, 45.0 * kDeg});
  rig.tick();
  CHECK(rig.exec.pose().x_m == Approx(5.5));
  CHECK(rig.exec.pose().y_m == Approx(5.0));
  CHECK(rig.exec.pose().theta_rad == Approx(90.0 * kDeg));
  // Move the robot by hand 1 m along its own heading: mission pose moves +y.
  rig.drive.true_x_m += 1.0;
  rig.drive.true_theta_rad += 0.1;
  rig.tick();
  CHECK(rig.exec.pose().x_m == Approx(5.5).epsilon(1e-9));
  CHECK(rig.exec.pose().y_m == Approx(6.0));
  CHECK(rig.exec.pose().theta_rad == Approx(90.0 * kDeg + 0.1 + 10.0 * kDeg * 0.1));
}

TEST_CASE("Spin + HasTurned: the accumulated turn fires the transition") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("turn", mission::SpinParams{30.0}).state("next", mission::StopParams{}).state("end", mission::StopParams{});
  r.transition("turn", "next", mission::HasTurnedParams{90.0, 1.5});  // fires at 88.5°
  r.transition("next", "end", mission::HasTurnedParams{1.0, 0.0});
  Rig rig(one_robot(r));
  rig.tick();
  CHECK(rig.exec.last_command().rot_radps == Approx(30.0 * kDeg));
  CHECK(rig.exec.last_command().trans_mps == 0.0);
  int cycles = 1;
  while (rig.exec.state_name() == "turn" && cycles < 100) {
    rig.tick();
    ++cycles;
  }
  // 3° per cycle after the first: 87° after cycle 30, 90° after cycle 31.
  CHECK(cycles == 31);
  // Entering "next" resets the accumulator: Stop does not turn, so it never fires.
  rig.ticks(10);
  CHECK(rig.exec.state_name() == "next");
  CHECK(rig.exec.turned_rad() == Approx(0.0));
}

TEST_CASE("transitions are checked in file order, at most one per cycle") {
  std::vector<mission::Message> messages{{"m1", 1, {0}}, {"m2", 1, {0}}};
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("a", mission::StopParams{}).state("via_m1", mission::StopParams{}).state("via_m2", mission::StopParams{});
  r.state("end", mission::StopParams{});
  r.transition("a", "via_m2", mission::NotifiedParams{"m2"});  // listed first
  r.transition("a", "via_m1", mission::NotifiedParams{"m1"});
  r.transition("via_m2", "end", mission::NotifiedParams{"m1"});
  r.transition("via_m1", "end", mission::NotifiedParams{"m1"});
  const auto m = with_teammate(r, messages);

  SUBCASE("both hold: the first listed fires, then the next state's trigger on the next cycle") {
    Rig rig(m);
    rig.tick();
    rig.link.deliver("robot2", "m1");
    rig.link.deliver("robot2", "m2");
    rig.tick();
    CHECK(rig.exec.state_name() == "via_m2");  // only one transition this cycle
    CHECK(rig.exec.transition_count() == 1);
    rig.tick();
    CHECK(rig.exec.state_name() == "end");
    CHECK(rig.exec.outcome().phase == Phase::finished);
  }
  SUBCASE("only the second holds: the second fires") {
    Rig rig(m);
    rig.tick();
    rig.link.deliver("robot2", "m1");
    rig.tick();
    CHECK(rig.exec.state_name() == "via_m1");
  }
  SUBCASE("a notification from the wrong sender or of an unknown message does not count") {
    Rig rig(m);
    rig.tick();
    rig.link.deliver("intruder", "m1");
    rig.link.deliver("robot2", "nonsense");
    rig.ticks(3);
    CHECK(rig.exec.state_name() == "a");
    CHECK_FALSE(rig.exec.messages().received(0));
  }
}

TEST_CASE("Notify: notify() once on entry with the message's recipients; MessageSent only after the ack") {
  std::vector<mission::Message> messages{{"arrived", 0, {1}}};
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("tell", mission::NotifyParams{"arrived"}).state("done", mission::StopParams{});
  r.transition("tell", "done", mission::MessageSentParams{"arrived"});
  Rig rig(with_teammate(r, messages));
  rig.tick();
  REQUIRE(rig.link.notify_calls.size() == 1);
  CHECK(rig.link.notify_calls[0].message == "arrived");
  CHECK(rig.link.notify_calls[0].recipients == std::vector<std::string>{"robot2"});
  CHECK(rig.exec.last_command().trans_mps == 0.0);  // zero motion
  CHECK(rig.exec.last_command().rot_radps == 0.0);
  rig.ticks(10);  // no ack yet
  CHECK(rig.exec.state_name() == "tell");
  CHECK(rig.link.notify_calls.size() == 1);  // on entry only, never repeated by the executive
  rig.link.ack(rig.link.notify_calls[0].seq, "robot2");
  rig.tick();
  CHECK(rig.exec.state_name() == "done");
  CHECK(rig.exec.outcome().phase == Phase::finished);
}

TEST_CASE("Notify that the link refuses aborts the mission") {
  std::vector<mission::Message> messages{{"arrived", 0, {1}}};
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("tell", mission::NotifyParams{"arrived"}).state("done", mission::StopParams{});
  r.transition("tell", "done", mission::MessageSentParams{"arrived"});
  Rig rig(with_teammate(r, messages));
  rig.link.fail_notify = true;
  rig.tick();
  CHECK(rig.exec.outcome().phase == Phase::aborted);
  CHECK(rig.exec.outcome().reason.find("arrived") != std::string::npos);
}

TEST_CASE("Notified is remembered: a message received before the waiting state still counts") {
  std::vector<mission::Message> messages{{"go", 1, {0}}};
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("drive", p3at::test::go_to(1.0, 0.0)).state("wait", mission::StopParams{}).state("end", mission::StopParams{});
  r.transition("drive", "wait", p3at::test::at_goal(1.0, 0.0, 0.1));
  r.transition("wait", "end", mission::NotifiedParams{"go"});
  Rig rig(with_teammate(r, messages));
  rig.tick();
  rig.link.deliver("robot2", "go");  // arrives while still driving
  rig.tick();
  CHECK(rig.exec.state_name() == "drive");
  CHECK(rig.exec.messages().received(0));
  int cycles = 0;
  while (rig.exec.state_name() == "drive" && cycles < 200) {
    rig.tick();
    ++cycles;
  }
  REQUIRE(rig.exec.state_name() == "wait");
  rig.tick();  // the very next cycle
  CHECK(rig.exec.state_name() == "end");
}

TEST_CASE("link loss aborts: stop(), no emergency stop, reason logged and published") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("drive", p3at::test::go_to(10.0, 0.0)).state("end", mission::StopParams{});
  r.transition("drive", "end", p3at::test::at_goal(10.0, 0.0, 0.2));
  Rig rig(one_robot(r));
  rig.ticks(5);
  CHECK(rig.drive.trans_cmd_mps > 0.0);
  rig.drive.set_link(p3at::hal::LinkState::link_lost, "no SIP for 1000 ms");
  const int calls = rig.drive.set_velocity_calls;
  rig.tick();
  CHECK(rig.exec.outcome().phase == Phase::aborted);
  CHECK(rig.exec.outcome().reason.find("link-lost") != std::string::npos);
  CHECK(rig.exec.outcome().reason.find("no SIP") != std::string::npos);
  CHECK(rig.drive.stop_calls == 1);
  CHECK(rig.drive.emergency_stop_calls == 0);
  CHECK(rig.drive.set_velocity_calls == calls);  // no motion command after the loss
  REQUIRE_FALSE(rig.link.status_sent.empty());
  CHECK(rig.link.status_sent.back().phase == "aborted");
  CHECK(rig.link.status_sent.back().reason == rig.exec.outcome().reason);
}

TEST_CASE("safety stop aborts") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("drive", p3at::test::go_to(10.0, 0.0));
  Rig rig(one_robot(never_ending(r, "drive")));
  rig.tick();
  rig.drive.set_link(p3at::hal::LinkState::safety_stop, "e-stop pressed");
  rig.tick();
  CHECK(rig.exec.outcome().phase == Phase::aborted);
  CHECK(rig.exec.outcome().reason == "safety stop: e-stop pressed");
}

TEST_CASE("a teammate's abort aborts this robot") {
  std::vector<mission::Message> messages{{"go", 1, {0}}};
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("wait", mission::StopParams{}).state("end", mission::StopParams{});
  r.transition("wait", "end", mission::NotifiedParams{"go"});
  Rig rig(with_teammate(r, messages));
  rig.ticks(3);
  rig.link.set_teammate_status(p3at::hal::TeamStatus{"robot2", "running", "idle", "", -1.0});
  rig.tick();
  CHECK(rig.exec.running());
  rig.link.set_teammate_status(p3at::hal::TeamStatus{"robot2", "aborted", "idle", "drive link link-lost", -1.0});
  rig.tick();
  CHECK(rig.exec.outcome().phase == Phase::aborted);
  CHECK(rig.exec.outcome().reason == "teammate robot2 aborted: drive link link-lost");
  CHECK(rig.drive.stop_calls == 1);
  CHECK(rig.exec.team_settled());
}

TEST_CASE("a refused motion command aborts") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("drive", p3at::test::go_to(10.0, 0.0));
  Rig rig(one_robot(never_ending(r, "drive")));
  rig.drive.refuse_motion = true;
  rig.tick();
  CHECK(rig.exec.outcome().phase == Phase::aborted);
  CHECK(rig.exec.outcome().reason.find("motion command refused") == 0);
  CHECK(rig.drive.stop_calls == 1);
}

TEST_CASE("abort() from outside (an interrupt) stops and publishes; later calls change nothing") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("drive", p3at::test::go_to(10.0, 0.0));
  Rig rig(one_robot(never_ending(r, "drive")));
  rig.ticks(3);
  rig.exec.abort("interrupted by SIGINT");
  CHECK(rig.exec.outcome().reason == "interrupted by SIGINT");
  CHECK(rig.link.status_sent.back().phase == "aborted");
  rig.exec.abort("again");
  CHECK(rig.exec.outcome().reason == "interrupted by SIGINT");
  // Still cycled afterwards: keeps polling the link (acks), commands nothing.
  const int polls = rig.link.poll_calls;
  const int calls = rig.drive.set_velocity_calls;
  rig.ticks(3);
  CHECK(rig.link.poll_calls == polls + 3);
  CHECK(rig.drive.set_velocity_calls == calls);
}

TEST_CASE("GoToGuarded's noise is world-fixed, held N cycles, and deterministic for a seed") {
  RobotBuilder r("robot1", {0, 0, 0});
  mission::GoToGuardedParams p = p3at::test::go_to(100.0, 0.0);
  p.move_gain = 0.0;  // noise only
  p.noise_gain = 1.0;
  p.noise_persistence_cycles = 4;
  r.state("wander", p);
  never_ending(r, "wander");
  p3at::exec::ExecutiveOptions options;
  options.seed = 99;
  Rig rig(one_robot(r), 0, options);
  p3at::exec::NoiseSource reference(99, "robot1");  // same seed, same robot: same draws
  p3at::exec::BehaviorConfig config;
  for (int i = 0; i < 12; ++i) {
    rig.tick();
    const auto dir = reference.next(4);
    const auto pose = rig.exec.pose();
    const auto expected = p3at::exec::vector_to_velocity(dir, pose.theta_rad, 0.3, config.max_rot_radps, config.rot_gain);
    CAPTURE(i);
    CHECK(rig.exec.last_command().trans_mps == Approx(expected.trans_mps));
    CHECK(rig.exec.last_command().rot_radps == Approx(expected.rot_radps));
  }
  CHECK(rig.exec.noise().draws() == 3);  // 12 cycles / 4
  // The robot turned while the direction was held, so the command changed within
  // a hold even though the direction did not: the direction is world-fixed.
  CHECK(std::abs(rig.exec.pose().theta_rad) > 0.05);
}

TEST_CASE("telemetry every N cycles, status heartbeat, transition callback") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("turn", mission::SpinParams{30.0}).state("end", mission::StopParams{});
  r.transition("turn", "end", mission::HasTurnedParams{30.0, 1.5});
  p3at::exec::ExecutiveOptions options;
  options.telemetry_every_cycles = 3;
  options.status_every_cycles = 0;
  std::vector<p3at::exec::TransitionEvent> events;
  options.on_transition = [&](const p3at::exec::TransitionEvent& e) { events.push_back(e); };
  Rig rig(one_robot(r), 0, options);
  rig.ticks(9);
  CHECK(rig.link.telemetry_sent.size() == 3);
  CHECK(rig.link.telemetry_sent.back().robot == "robot1");
  CHECK(rig.link.telemetry_sent.back().state == "turn");
  CHECK(rig.link.telemetry_sent.back().theta_rad == Approx(rig.exec.pose().theta_rad));
  CHECK(rig.link.status_sent.size() == 1);  // "running" on entering the initial state only
  CHECK(rig.link.status_sent[0].phase == "running");
  rig.ticks(5);
  REQUIRE(events.size() == 1);
  CHECK(events[0].from == 0);
  CHECK(events[0].to == 1);
  CHECK(events[0].cause == mission::TriggerKind::has_turned);
  CHECK(events[0].t_s == Approx(1.0));  // 30° at 30°/s, cycle 11 at t = 1.0 s
}

TEST_CASE("cycle statistics: cycles, missed updates, percentiles in telemetry") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("idle", mission::StopParams{});
  Rig rig(one_robot(never_ending(r, "idle")));
  rig.ticks(5);
  // Two cycles with no new update from the drive base.
  rig.clock.advance_us(100'000);
  rig.exec.cycle();
  rig.clock.advance_us(100'000);
  rig.exec.cycle();
  rig.tick();
  CHECK(rig.exec.stats().cycles() == 8);
  CHECK(rig.exec.stats().missed_updates() == 2);
  CHECK(rig.exec.stats().p50_us() > 0.0);
  CHECK(rig.exec.stats().p99_us() >= rig.exec.stats().p50_us());
  CHECK(rig.exec.stats().overruns() == 0);  // microseconds of work in a 100 ms period
  const auto& t = rig.link.telemetry_sent.back();
  CHECK(t.cycles == 7);  // published before this cycle's own sample
  CHECK(t.missed_updates == 2);
  CHECK(t.cycle_p99_us > 0.0);
}

TEST_CASE("a poll error is reported, not fatal") {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("idle", mission::StopParams{});
  Rig rig(one_robot(never_ending(r, "idle")));
  rig.link.poll_error = true;
  rig.ticks(3);
  CHECK(rig.exec.running());
  CHECK(rig.link.poll_calls == 3);
}
