// Hardware-in-the-loop: p3at_sim serving two robots, two separate mission_exec
// processes talking over real LCM multicast (loopback, ttl=0) and real TCP,
// passing the launch gate and completing the relay mission; a forged
// notification from a third process, without the team key, is rejected and
// fires nothing. (The gate's own paths: test_launch_gate_sitl.cpp.)
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "child_process.hpp"
#include "sim_fixture.hpp"
#include "team_fixture.hpp"

using namespace p3at;
using test::final_truth;
using test::kRelayMission;
using test::kRelayModels;
using test::kRelayWorld;

TEST_CASE("relay: two mission_exec processes over real LCM and TCP; a forged notification is rejected") {
  const std::string key = test::make_key("team.key");
  const std::string wrong_key = test::make_key("intruder.key");
  const int port = test::free_port_pair();
  const std::string lcm = test::fresh_lcm_url();

  test::SimProcess sim({"--world", kRelayWorld, "--speedup", "2"}, port);
  REQUIRE(sim.ready());
  REQUIRE(sim.process.wait_for_log("port=" + std::to_string(port + 1), 5.0));

  const auto exec_args = [&](const std::string& robot, int robot_port) {
    return test::exec_args(robot, robot_port, lcm, key, kRelayMission, {"--models", kRelayModels});
  };
  test::ChildProcess robot2(exec_args("robot2", port + 1), test::scratch_path("robot2.log"));
  REQUIRE(robot2.wait_for_log("event=gate-open", 10.0));

  // An intruder claiming to be robot1, signing with the wrong key.
  test::ChildProcess forger({P3AT_TEAM_PEER_BIN, "run", "--url", lcm, "--mission", "relay", "--name", "robot1",
                             "--roster", "robot1,robot2", "--key", wrong_key, "--notify", "r1_done", "--to", "robot2",
                             "--duration-s", "1.5", "--publish-ms", "200"},
                            test::scratch_path("forger.log"));
  CHECK(forger.wait_exit(10.0) == 0);
  // robot2 is still waiting: the forgery fired nothing.
  CHECK(robot2.running());
  CHECK(robot2.log().find("to=drive") == std::string::npos);

  test::ChildProcess robot1(exec_args("robot1", port), test::scratch_path("robot1.log"));
  CHECK(robot1.wait_exit(90.0) == 0);
  CHECK(robot2.wait_exit(90.0) == 0);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  CHECK(log1.find("event=finished robot=robot1 outcome=finished") != std::string::npos);
  CHECK(log2.find("event=finished robot=robot2 outcome=finished") != std::string::npos);
  CHECK(log2.find("cause=Notified") != std::string::npos);
  // The forged notification was rejected and counted by robot2.
  CHECK(log2.find("rejected_bad_tag=0 ") == std::string::npos);
  CHECK(log2.find("rejected_bad_tag=") != std::string::npos);
  // The robots really are near their goals (simulator ground truth).
  const auto [x1, y1] = final_truth(sim.truth_path, "robot1");
  const auto [x2, y2] = final_truth(sim.truth_path, "robot2");
  CHECK(std::hypot(x1 - 3.0, y1 - 1.0) < 0.6);
  CHECK(std::hypot(x2 - 3.0, y2 - 3.0) < 0.6);
}
