#pragma once
// What the launch-gate hardware-in-the-loop tests share: p3at_sim serving the
// relay's two robots on two fresh ports, a team key, a fresh LCM URL,
// mission_exec's command line, and the simulator's confirmation that no robot
// received a motion command.

#include <csignal>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "p3at/launch_gate/mission_hash.hpp"
#include "sim_fixture.hpp"
#include "team_fixture.hpp"

namespace p3at::test {

inline constexpr int kExitAborted = 3;
inline constexpr int kExitGateNoGo = 4;
inline constexpr int kExitGateMismatch = 5;
inline constexpr int kExitGateSilent = 6;
inline constexpr int kExitGateInDoubt = 8;

inline std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + needle.size())) ++n;
  return n;
}

/// p3at_sim with the relay world on two fresh ports, a team key and an LCM URL.
struct Bench {
  std::string key = make_key("team.key");
  int port = free_port_pair();
  std::string lcm = fresh_lcm_url();
  SimProcess sim{{"--world", kRelayWorld, "--speedup", "4"}, port};

  Bench() {
    REQUIRE(sim.ready());
    REQUIRE(sim.process.wait_for_log("port=" + std::to_string(port + 1), 5.0));
  }
  std::vector<std::string> args(const std::string& robot, std::vector<std::string> extra = {},
                                const std::string& mission = kRelayMission) const {
    extra.insert(extra.begin(), {"--models", kRelayModels});
    return exec_args(robot, robot == "robot1" ? port : port + 1, lcm, key, mission, extra);
  }
  /// Stops the simulator and checks, from its truth CSV and its final stats,
  /// that neither robot ever received a motion command.
  void check_no_motion() {
    CHECK(motion_commands(sim.truth_path, "robot1") == 0);
    CHECK(motion_commands(sim.truth_path, "robot2") == 0);
    sim.process.signal(SIGTERM);
    CHECK(sim.process.wait_exit(10.0) == 0);
    const std::string log = sim.process.log();
    INFO("simulator log:\n" << log);
    // One stats line per robot at exit, each with its count of motion commands.
    CHECK(occurrences(log, "[p3at_sim] stats robot=") == 2);
    CHECK(occurrences(log, " motion_commands=0 ") == 2);
  }
};

inline std::string relay_hash() {
  return gate::mission_content_hash(gate::read_file_bytes(kRelayMission).value(),
                                    gate::read_file_bytes(kRelayModels).value(), {});
}

}  // namespace p3at::test
