// Faults during a mission, on real processes (docs/executive.md, "Stalls" and
// "Liveness"): p3at_sim with the relay's two robots (--speedup 4), two
// mission_exec over real LCM on the loopback and real TCP.
//  - robot1 frozen with SIGSTOP for 3 s while driving (12 s of controller
//    time, past the firmware's 2 s watchdog): on SIGCONT it logs and counts
//    the stall, resynchronises on the newest SIP and aborts; the simulator
//    counts at most 6 motion commands after the freeze (before: dozens,
//    replayed from stale SIPs);
//  - a 0.3 s freeze: logged and counted, the mission goes on and finishes;
//  - a 3 s freeze with --resume-after-stall: said, and the mission finishes;
//  - robot1 killed mid-mission: robot2 reports it silent within the limit
//    and, the mission saying stop_and_notify, aborts;
//  - SIGHUP (a closed terminal): handled like SIGTERM, the summary printed,
//    the abort reaches the teammate.
// Wall time: about 60 s (sitl label, TIMEOUT 300).
#include <doctest/doctest.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "gate_bench.hpp"

using namespace p3at;
using test::contains;

namespace {

/// The relay with abort_action: stop_and_notify (a new file, so a new hash).
std::string stop_and_notify_relay() {
  const std::string path = test::scratch_path("relay-stop.yaml");
  std::string text = gate::read_file_bytes(test::kRelayMission).value();
  const std::string anchor = "  threshold: 0.8";
  const auto at = text.find(anchor);
  REQUIRE(at != std::string::npos);
  text.insert(text.find('\n', at) + 1, "  abort_action: stop_and_notify\n");
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

void sleep_s(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

/// `args` once `first` has opened its gate (so robot1 starts second).
std::vector<std::string> after_gate_open(test::ChildProcess& first, std::vector<std::string> args) {
  REQUIRE(first.wait_for_log("event=gate-open", 15.0));
  return args;
}

/// Starts robot2 then robot1 and waits until both have launched.
struct Team {
  test::Bench& bench;
  test::ChildProcess robot2;
  test::ChildProcess robot1;
  Team(test::Bench& b, std::vector<std::string> extra1, std::vector<std::string> extra2,
       const std::string& mission = test::kRelayMission)
      : bench(b),
        robot2(b.args("robot2", extra2, mission), test::scratch_path("robot2.log")),
        robot1(after_gate_open(robot2, b.args("robot1", extra1, mission)), test::scratch_path("robot1.log")) {
    REQUIRE(robot1.wait_for_log("event=launch", 20.0));
    REQUIRE(robot2.wait_for_log("event=launch", 20.0));
  }
};

/// Freezes robot1 for `freeze_s` about 1 s into its drive; returns its motion
/// commands (from the simulator) at the moment it was frozen.
long long freeze_robot1(Team& team, double freeze_s) {
  sleep_s(1.0);
  const long long before = test::motion_commands(team.bench.sim.truth_path, "robot1");
  team.robot1.signal(SIGSTOP);
  sleep_s(freeze_s);
  team.robot1.signal(SIGCONT);
  return before;
}

}  // namespace

TEST_CASE("a 3 s freeze (past the firmware watchdog): stall logged and counted, no stale replay, mission aborted") {
  test::Bench bench;
  Team team(bench, {}, {});
  const long long before = freeze_robot1(team, 3.0);
  CHECK(team.robot1.wait_exit(30.0) == test::kExitAborted);
  CHECK(team.robot2.wait_exit(30.0) == test::kExitAborted);  // robot1's abort stops its teammate
  const std::string log1 = team.robot1.log();
  INFO("robot1 log:\n" << log1);
  CHECK(before > 0);  // it was driving
  CHECK(contains(log1, "event=stall robot=robot1"));
  CHECK(contains(log1, "resynchronised on the newest update"));
  CHECK(contains(log1, "outcome=aborted"));
  CHECK(contains(log1, "longer than the firmware watchdog"));
  CHECK_FALSE(contains(log1, " stalls=0 "));
  CHECK_FALSE(contains(log1, " missed_cycles=0 "));
  // No motion from stale SIPs: a few commands at most (VEL and RVEL of the
  // cycle or two between reading the count and the SIGSTOP; before: 44).
  const long long after = test::motion_commands(bench.sim.truth_path, "robot1");
  INFO("motion commands at the freeze " << before << ", at the end " << after);
  CHECK(after - before <= 6);
}

TEST_CASE("a 0.3 s freeze is logged and counted; the mission goes on and finishes") {
  test::Bench bench;
  Team team(bench, {}, {"--teammate-silence-s", "10"});
  freeze_robot1(team, 0.3);
  CHECK(team.robot1.wait_exit(60.0) == 0);
  CHECK(team.robot2.wait_exit(60.0) == 0);
  const std::string log1 = team.robot1.log();
  INFO("robot1 log:\n" << log1);
  CHECK(contains(log1, "event=stall robot=robot1"));
  CHECK_FALSE(contains(log1, " stalls=0 "));
  CHECK(contains(log1, "outcome=finished"));
}

TEST_CASE("--resume-after-stall: a 3 s freeze is said, and the mission finishes") {
  test::Bench bench;
  Team team(bench, {"--resume-after-stall"}, {"--teammate-silence-s", "10"});
  freeze_robot1(team, 3.0);
  CHECK(team.robot1.wait_exit(60.0) == 0);
  CHECK(team.robot2.wait_exit(60.0) == 0);
  const std::string log1 = team.robot1.log();
  INFO("robot1 log:\n" << log1);
  CHECK(contains(log1, "event=stall-resume robot=robot1"));
  CHECK(contains(log1, "outcome=finished"));
}

TEST_CASE("a teammate killed mid-mission: reported silent within the limit, and stop_and_notify aborts the survivor") {
  test::Bench bench;
  const std::string mission = stop_and_notify_relay();
  Team team(bench, {}, {"--teammate-silence-s", "1.5"}, mission);
  sleep_s(0.5);
  team.robot1.signal(SIGKILL);
  const auto killed = std::chrono::steady_clock::now();
  CHECK(team.robot2.wait_exit(20.0) == test::kExitAborted);
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  const std::string log2 = team.robot2.log();
  INFO("robot2 log:\n" << log2);
  CHECK(contains(log2, "event=teammate-silent robot=robot2 teammate=robot1"));
  CHECK(contains(log2, "reason=\"teammate robot1 silent for"));
  CHECK(took_s < 6.0);  // 1.5 s limit, then the abort and the final status
}

TEST_CASE("SIGHUP is handled like SIGTERM: summary printed, abort sent, the teammate stops too") {
  test::Bench bench;
  Team team(bench, {}, {});
  sleep_s(0.5);
  team.robot1.signal(SIGHUP);
  CHECK(team.robot1.wait_exit(20.0) == test::kExitAborted);
  CHECK(team.robot2.wait_exit(20.0) == test::kExitAborted);
  const std::string log1 = team.robot1.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << team.robot2.log());
  CHECK(contains(log1, "event=finished robot=robot1 outcome=aborted"));
  CHECK(contains(log1, "interrupted by signal"));
  CHECK(contains(log1, "event=team-link robot=robot1"));
  CHECK(contains(team.robot2.log(), "outcome=aborted"));
}
