// Whole missions with one robot on a real serial driver (serial rig,
// docs/hal.md): p3at_sim serves robot1 on the serial line's far end and
// robot2 on TCP; two mission_exec processes in the same kernel talk over real
// LCM multicast on the loopback (ttl=0) and pass the launch gate. Then the
// serial cable is pulled mid-mission: robot1 must notice within the link-loss
// time, abort, and its teammate must hear of it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rig_sim.hpp"
#include "serial_rig.hpp"
#include "sim_fixture.hpp"
#include "team_fixture.hpp"

using namespace p3at;
using namespace p3at::test::serial_rig;
using p3at::test::ChildProcess;
using p3at::test::scratch_path;

namespace {

constexpr int kExitAborted = 3;       // mission_exec: aborted during the mission
constexpr int kLinkLossMs = 1000;     // ArcosClient's default link_loss_ms
constexpr int kDetectSlackMs = 800;   // its loop period and the emulated machine's stalls on top

/// mission_exec for `robot` with the given drive URL (robot1: the serial line).
std::vector<std::string> exec_for(const std::string& robot, const std::string& hal, const std::string& lcm,
                                  const std::string& key) {
  std::vector<std::string> args = test::exec_args(robot, 0, lcm, key, test::kRelayMission, {"--models", test::kRelayModels});
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--hal") args[i + 1] = hal;
  }
  return args;
}

std::string tcp_url(int port) { return "tcp://127.0.0.1:" + std::to_string(port); }

/// robot1's latest true x in the truth CSV (NAN before the first row).
double true_x(const std::string& csv) { return test::final_truth(csv, "robot1").first; }

}  // namespace

TEST_CASE("relay: robot1 on /dev/ttyS0 and robot2 on TCP complete the mission over real LCM") {
  const std::string key = test::make_key("team.key");
  const std::string lcm = test::fresh_lcm_url();
  SimOnPeerPort sim({"--world", test::kRelayWorld, "--speedup", "2"});
  REQUIRE_MESSAGE(sim.line_connected(1), sim.process.log());
  const int tcp_port = peer_port() + 1;
  REQUIRE(sim.process.wait_for_log("port=" + std::to_string(tcp_port), 5.0));

  ChildProcess robot2(exec_for("robot2", tcp_url(tcp_port), lcm, key), scratch_path("robot2.log"));
  ChildProcess robot1(exec_for("robot1", url(9600), lcm, key), scratch_path("robot1.log"));
  const int rc1 = robot1.wait_exit(90.0);
  const int rc2 = robot2.wait_exit(60.0);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  CHECK(rc1 == 0);
  CHECK(rc2 == 0);
  CHECK(test::contains(log1, "hal=" + url(9600)));
  CHECK(test::contains(log1, "event=finished robot=robot1 outcome=finished"));
  CHECK(test::contains(log2, "event=finished robot=robot2 outcome=finished"));
  CHECK(test::contains(log2, "cause=Notified"));
  const auto [x1, y1] = test::final_truth(sim.truth_path, "robot1");
  const auto [x2, y2] = test::final_truth(sim.truth_path, "robot2");
  INFO("robot1 motion commands received: " << test::motion_commands(sim.truth_path, "robot1"));
  CHECK(std::hypot(x1 - 3.0, y1 - 1.0) < 0.6);
  CHECK(std::hypot(x2 - 3.0, y2 - 3.0) < 0.6);
}

TEST_CASE("relay: the serial cable pulled mid-mission is noticed within the link-loss time and aborts the team") {
  const std::string key = test::make_key("team.key");
  const std::string lcm = test::fresh_lcm_url();
  const int sim_port = test::free_port_pair();
  test::SimProcess sim({"--world", test::kRelayWorld, "--speedup", "2"}, sim_port);
  REQUIRE(sim.ready());
  REQUIRE(sim.process.wait_for_log("port=" + std::to_string(sim_port + 1), 5.0));

  // The cable: the serial line's far end relayed to robot1's port until pulled.
  std::atomic<bool> pulled{false};
  std::atomic<std::int64_t> pulled_at_ms{0};
  std::atomic<std::uint64_t> relayed{0};
  FarEnd cable([&](hal::ByteStream& line, const std::atomic<bool>& stop) {
    auto opened = hal::open_byte_stream(tcp_url(sim_port));
    if (!opened.ok()) return;
    auto& robot = *opened.value();
    std::vector<std::uint8_t> buffer(512);
    while (!stop && !pulled) {
      auto from_line = line.read_some(buffer, 5);
      if (!from_line.ok()) return;
      if (*from_line > 0 && !robot.write_all(std::span<const std::uint8_t>(buffer.data(), *from_line)).ok()) return;
      auto from_robot = robot.read_some(buffer, 0);
      if (!from_robot.ok()) return;
      if (*from_robot > 0 && !line.write_all(std::span<const std::uint8_t>(buffer.data(), *from_robot)).ok()) return;
      relayed += *from_line + *from_robot;
    }
    pulled_at_ms = steady_ms();
    robot.close();  // both ends go; the FarEnd stops listening, so QEMU cannot reconnect
  });
  REQUIRE_MESSAGE(cable.wait_connected(), cable.listen_error());

  ChildProcess robot2(exec_for("robot2", tcp_url(sim_port + 1), lcm, key), scratch_path("robot2.log"));
  ChildProcess robot1(exec_for("robot1", url(19200), lcm, key), scratch_path("robot1.log"));
  // Pull the cable once robot1 is well on its way (it starts at x = 1 m, goal 3 m).
  const std::int64_t give_up = steady_ms() + 60000;
  while (!(true_x(sim.truth_path) > 1.5) && robot1.running() && robot2.running() && steady_ms() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  INFO("robot1 log:\n" << robot1.log());
  INFO("robot2 log:\n" << robot2.log());
  INFO("p3at_sim log:\n" << sim.process.log());
  // Motion commands robot1's firmware took: many with no motion means its
  // motors stayed disabled (an ENABLE lost on the line).
  INFO("robot1 motion commands received: " << test::motion_commands(sim.truth_path, "robot1"));
  REQUIRE(true_x(sim.truth_path) > 1.5);
  pulled = true;
  cable.stop();
  REQUIRE(pulled_at_ms > 0);

  // Noticed: the link-lost line appears within the link-loss time (plus slack).
  REQUIRE(robot1.wait_for_log("event=link-lost", 10.0));
  const std::int64_t noticed_ms = steady_ms() - pulled_at_ms;
  const int rc1 = robot1.wait_exit(30.0);
  const int rc2 = robot2.wait_exit(30.0);
  const std::string log1 = robot1.log();
  const std::string log2 = robot2.log();
  INFO("robot1 log:\n" << log1);
  INFO("robot2 log:\n" << log2);
  MESSAGE("cable pulled at x=" << true_x(sim.truth_path) << " m after " << relayed.load()
                               << " relayed bytes; link loss noticed after <= " << noticed_ms << " ms");
  INFO("noticed after " << noticed_ms << " ms");
  CHECK(noticed_ms <= kLinkLossMs + kDetectSlackMs);
  int silence_ms = -1;
  const std::size_t at = log1.find("why=\"no SIP for ");
  REQUIRE(at != std::string::npos);
  CHECK(std::sscanf(log1.c_str() + at, "why=\"no SIP for %d ms", &silence_ms) == 1);
  CHECK(silence_ms >= kLinkLossMs);
  CHECK(silence_ms <= kLinkLossMs + kDetectSlackMs);
  // robot1 aborted on its lost drive link; robot2 heard it over LCM and aborted too.
  CHECK(rc1 == kExitAborted);
  CHECK(test::contains(log1, "event=finished robot=robot1 outcome=aborted"));
  CHECK(test::contains(log1, "drive link link-lost"));
  CHECK(rc2 == kExitAborted);
  CHECK(test::contains(log2, "teammate robot1 aborted"));
  CHECK_FALSE(test::contains(log2, "to=drive"));
  // The robot stopped short of its goal once its session was gone.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  CHECK(true_x(sim.truth_path) < 2.8);
}
