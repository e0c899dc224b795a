// Hardware-in-the-loop tests of the launch gate (docs/launch-gate.md): p3at_sim
// serving two robots, mission_exec processes over real LCM multicast (loopback,
// ttl=0) and real TCP. GO: the team agrees, launches, completes the relay and
// re-verifies on the way. Every refusal: no robot moves, confirmed by the
// simulator's own count of motion commands received — a NO-GO (one robot's
// verdict), a mismatched mission hash, a silent teammate, and a forged GO from
// a process without the team key (rejected and counted). And the operator's
// override, logged and published as OVERRIDE. And a mission the model does
// not vouch for (max_speed_mps above the P3-AT's top speed): cannot evaluate,
// exit 7, no robot moves.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <chrono>
#include <string>
#include <thread>

#include "child_process.hpp"
#include "p3at/launch_gate/mission_hash.hpp"
#include "gate_bench.hpp"

using namespace p3at;
using test::Bench;
using test::kExitGateCannotRun;
using test::kExitGateMismatch;
using test::kExitGateNoGo;
using test::kExitGateSilent;
using test::relay_hash;
using test::contains;
using test::kRelayMission;
using test::kRelayModels;
using test::kRelayWorld;


TEST_CASE("GO: both robots verify the same hash, launch together, complete the relay and re-verify on the way") {
  Bench bench;
  test::ChildProcess robot2(bench.args("robot2"), test::scratch_path("robot2.log"));
  REQUIRE(robot2.wait_for_log("event=gate-open", 15.0));
  test::ChildProcess robot1(bench.args("robot1"), test::scratch_path("robot1.log"));
  CHECK(robot1.wait_exit(90.0) == 0);
  CHECK(robot2.wait_exit(90.0) == 0);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  const std::string hash = relay_hash();
  for (const std::string* log : {&log1, &log2}) {
    CHECK(contains(*log, "event=gate-check"));
    CHECK(contains(*log, "decision=GO p_time="));
    CHECK(contains(*log, "hash=" + hash));
    CHECK(contains(*log, "state=launch"));
    CHECK(contains(*log, "event=verdict-heard"));
    CHECK(contains(*log, "event=reverify "));  // at least one transition each, re-verified
  }
  CHECK(contains(log1, "every robot agrees: robot1:GO,robot2:GO"));
  CHECK(contains(log2, "every robot agrees: robot2:GO,robot1:GO"));
  CHECK(contains(log1, "event=finished robot=robot1 outcome=finished"));
  CHECK(contains(log2, "event=finished robot=robot2 outcome=finished"));
  CHECK(contains(log2, "cause=Notified"));
  CHECK_FALSE(contains(log1, "verdicts_accepted=0 "));
  // The robots really are near their goals (simulator ground truth), and moved.
  const auto [x1, y1] = test::final_truth(bench.sim.truth_path, "robot1");
  const auto [x2, y2] = test::final_truth(bench.sim.truth_path, "robot2");
  CHECK(std::hypot(x1 - 3.0, y1 - 1.0) < 0.6);
  CHECK(std::hypot(x2 - 3.0, y2 - 3.0) < 0.6);
  CHECK(test::motion_commands(bench.sim.truth_path, "robot1") > 10);
}

TEST_CASE("NO-GO: one robot's Tmax is too tight; neither robot moves, the simulator confirms it") {
  Bench bench;
  // robot2 alone finds the mission cannot meet a 5 s Tmax; robot1 verifies GO.
  test::ChildProcess robot1(bench.args("robot1"), test::scratch_path("robot1.log"));
  REQUIRE(robot1.wait_for_log("event=gate-open", 15.0));
  test::ChildProcess robot2(bench.args("robot2", {"--tmax", "5"}), test::scratch_path("robot2.log"));
  CHECK(robot2.wait_exit(30.0) == kExitGateNoGo);
  CHECK(robot1.wait_exit(30.0) == kExitGateNoGo);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  // The refusal prints the probability, the threshold and the failed criterion.
  CHECK(contains(log2, "NO-GO  mission relay"));
  CHECK(contains(log2, "P(done by Tmax = 5.0 s)"));
  CHECK(contains(log2, "< threshold 0.8000"));
  CHECK(contains(log2, "failed: P(t <= 5.0 s"));
  CHECK(contains(log2, "event=gate-refused robot=robot2 why=no-go"));
  CHECK(contains(log1, "event=gate-refused robot=robot1 why=no-go"));
  CHECK(contains(log1, "teammate robot2 says NO-GO"));
  // A robot whose own verdict is NO-GO never even connects to its base.
  CHECK_FALSE(contains(bench.sim.process.log(), "connect robot=robot2"));
  bench.check_no_motion();
}

TEST_CASE("mismatched hash: robot2 was given a different mission file; neither robot moves") {
  Bench bench;
  // The same mission with one more comment line: the same FSA, a different file.
  const std::string other = test::scratch_path("relay-edited.yaml");
  {
    std::ofstream out(other, std::ios::binary);
    out << gate::read_file_bytes(kRelayMission).value() << "# edited on robot2 only\n";
  }
  test::ChildProcess robot1(bench.args("robot1"), test::scratch_path("robot1.log"));
  REQUIRE(robot1.wait_for_log("event=gate-open", 15.0));
  test::ChildProcess robot2(bench.args("robot2", {}, other), test::scratch_path("robot2.log"));
  CHECK(robot1.wait_exit(30.0) == kExitGateMismatch);
  CHECK(robot2.wait_exit(30.0) == kExitGateMismatch);
  const std::string log1 = robot1.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << robot2.log());
  CHECK(contains(log1, "event=gate-refused robot=robot1 why=mismatch"));
  CHECK(contains(log1, "teammate robot2 verified a different mission or models"));
  CHECK(contains(robot2.log(), "why=mismatch"));
  bench.check_no_motion();
  std::filesystem::remove(other);
}

TEST_CASE("silent teammate: only robot1 runs; after --gate-timeout it refuses, and never moved") {
  Bench bench;
  test::ChildProcess robot1(bench.args("robot1", {"--gate-timeout", "3"}), test::scratch_path("robot1.log"));
  CHECK(robot1.wait_exit(30.0) == kExitGateSilent);
  const std::string log1 = robot1.log();
  INFO("robot1 log:\n" << log1);
  CHECK(contains(log1, "event=gate-refused robot=robot1 why=silent"));
  CHECK(contains(log1, "no verdict from robot2 within 3.0 s"));
  CHECK(contains(bench.sim.process.log(), "connect robot=robot1"));  // it was ready, connected, and held still
  bench.check_no_motion();
}

TEST_CASE("a forged GO from a process without the team key is rejected and counted; no launch") {
  Bench bench;
  const std::string wrong_key = test::make_key("intruder.key");
  test::ChildProcess robot1(bench.args("robot1", {"--gate-timeout", "4"}), test::scratch_path("robot1.log"));
  REQUIRE(robot1.wait_for_log("event=gate-open", 15.0));
  // The intruder claims to be robot2 and says GO for the very mission hash robot1 verified.
  test::ChildProcess forger({P3AT_TEAM_PEER_BIN, "run", "--url", bench.lcm, "--mission", "relay", "--name", "robot2",
                             "--roster", "robot1,robot2", "--key", wrong_key, "--verdict", "GO", "--hash",
                             relay_hash(), "--duration-s", "3", "--publish-ms", "100"},
                            test::scratch_path("forger.log"));
  CHECK(forger.wait_exit(15.0) == 0);
  CHECK(robot1.wait_exit(30.0) == kExitGateSilent);
  const std::string log1 = robot1.log();
  INFO("robot1 log:\n" << log1);
  INFO("forger log:\n" << forger.log());
  CHECK(contains(log1, "why=silent"));
  CHECK_FALSE(contains(log1, "event=verdict-heard"));
  CHECK(contains(log1, "verdicts_accepted=0 "));
  CHECK(contains(log1, "rejected_bad_tag="));
  CHECK_FALSE(contains(log1, "rejected_bad_tag=0 "));
  bench.check_no_motion();
}

TEST_CASE("operator override: both robots told --override-gate launch a NO-GO mission, logged and published as OVERRIDE") {
  Bench bench;
  const std::vector<std::string> extra{"--tmax", "5", "--override-gate"};
  test::ChildProcess robot2(bench.args("robot2", extra), test::scratch_path("robot2.log"));
  REQUIRE(robot2.wait_for_log("event=gate-open", 15.0));
  test::ChildProcess robot1(bench.args("robot1", extra), test::scratch_path("robot1.log"));
  CHECK(robot1.wait_exit(90.0) == 0);
  CHECK(robot2.wait_exit(90.0) == 0);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  CHECK(contains(log1, "event=gate-override robot=robot1 verifier_decision=NO-GO"));
  CHECK(contains(log2, "event=gate-override robot=robot2 verifier_decision=NO-GO"));
  CHECK(contains(log1, "event=verdict-heard robot=robot2 decision=OVERRIDE"));
  CHECK(contains(log1, "every robot agrees: robot1:OVERRIDE,robot2:OVERRIDE"));
  CHECK(contains(log2, "event=finished robot=robot2 outcome=finished"));
}

TEST_CASE("cannot evaluate: a mission faster than the robots' top speed; both refuse with exit 7, neither moves") {
  Bench bench;
  const std::string mission = std::string(P3AT_SOURCE_DIR) + "/tests/sitl/data/relay_too_fast.yaml";
  test::ChildProcess robot1(bench.args("robot1", {}, mission), test::scratch_path("robot1.log"));
  test::ChildProcess robot2(bench.args("robot2", {}, mission), test::scratch_path("robot2.log"));
  CHECK(robot1.wait_exit(30.0) == kExitGateCannotRun);
  CHECK(robot2.wait_exit(30.0) == kExitGateCannotRun);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  // The speed shows in the mission file, so each robot refuses before
  // evaluating (in milliseconds, no probability computed), saying why and where.
  CHECK(contains(log1, "CANNOT EVALUATE  mission relay_too_fast: the model does not vouch for it; refused before evaluating"));
  CHECK(contains(log1, "decision=cannot-evaluate evaluated=false"));
  CHECK(contains(log1, "UNVOUCHED approximation speed-above-top: robot1 at " + mission + ":"));
  CHECK(contains(log1, "event=gate-refused robot=robot1 why=cannot-evaluate"));
  CHECK(contains(log2, "event=gate-refused robot=robot2 why=cannot-evaluate"));
  CHECK(contains(log1, "unvouched=speed-above-top"));
  // Both refused before connecting, at once: give the simulator's truth CSV
  // its first rows (it records even unconnected robots) before reading it.
  for (int i = 0; i < 50 && (test::truth_rows(bench.sim.truth_path, "robot1").empty() ||
                             test::truth_rows(bench.sim.truth_path, "robot2").empty());
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  bench.check_no_motion();
}
