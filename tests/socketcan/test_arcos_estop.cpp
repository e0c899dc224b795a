// The whole chain on real kernels and real processes: our ARCOS client
// (bridge::ArcosClient) drives p3at_sim over TCP, wrapped by the accessories'
// GuardedDriveBase; p3at_can_sim's safety node on vcan0 is pressed and the
// firmware receives ESTOP within one SIP cycle, stops and reports it.
#include <doctest/doctest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <string>

#include "can_sim_process.hpp"
#include "can_test_env.hpp"
#include "p3at/bridge/accessories/accessory_hub.hpp"
#include "p3at/bridge/accessories/guarded_drive_base.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/clock.hpp"

namespace bridge = p3at::bridge;
namespace hal = p3at::hal;
using p3at::test::can_url;

namespace {

// A free TCP port on the loopback (bound, read, released: a tiny race, fine here).
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
  socklen_t len = sizeof addr;
  REQUIRE(::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0);
  ::close(fd);
  return ntohs(addr.sin_port);
}

int listening_port(p3at::test::Child& sim) {
  REQUIRE_MESSAGE(sim.wait_for_log(" port=", 10.0), "p3at_sim did not start:\n" << sim.log());
  const std::string log = sim.log();
  const std::size_t at = log.find(" port=") + 6;
  const std::size_t end = log.find_first_not_of("0123456789", at);
  REQUIRE(end > at);
  return std::stoi(log.substr(at, end - at));
}

}  // namespace

TEST_CASE("an e-stop on the CAN safety node reaches the firmware within one SIP cycle") {
  p3at::test::Child firmware({P3AT_SIM_BIN, "--port", std::to_string(free_port())});
  const std::string url = "tcp://127.0.0.1:" + std::to_string(listening_port(firmware));
  p3at::test::CanSimProcess nodes;

  hal::SteadyClock clock;
  bridge::ArcosClient client([url] { return hal::open_byte_stream(url); }, clock);
  auto connected = client.connect();
  REQUIRE_MESSAGE(connected, (connected ? "" : connected.error().message));

  auto bus = hal::open_can_bus(can_url());
  REQUIRE(bus);
  bridge::AccessoryHub hub(**bus);
  REQUIRE(hub.start());
  bridge::GuardedDriveBase robot(client, hub, clock, [&] { return client.enable_motors(true); },
                                 bridge::GuardConfig{10, true, true, "safety"});
  auto cycles = [&](int n) {
    for (int i = 0; i < n; ++i) REQUIRE(robot.wait_for_update(500));
  };
  for (int i = 0; i < 30 && !robot.verdict().clear; ++i) cycles(1);
  REQUIRE_MESSAGE(robot.rearm(), robot.verdict().why);
  REQUIRE(robot.set_velocity(0.3, 0.0));
  cycles(10);
  CHECK(client.state().trans_vel_mps > 0.1);
  CHECK(client.state().motors_enabled);

  const std::int64_t pressed_us = clock.now_us();
  nodes.command("estop on");
  for (int i = 0; i < 10 && robot.emergency_stops() == 0; ++i) cycles(1);
  REQUIRE(robot.emergency_stops() == 1);
  // From the e-stop message's arrival (kernel timestamp) to ESTOP sent to the firmware.
  const std::int64_t reaction_us = robot.last_stop_us() - hub.safety().last_trip().state_stamp_us;
  CAPTURE(reaction_us);
  CAPTURE(robot.last_stop_us() - pressed_us);
  CHECK(reaction_us >= 0);
  CHECK(reaction_us < 100'000);
  CHECK(robot.last_stop_us() - pressed_us < 1'000'000);  // including p3at_can_sim reading its stdin
  // The firmware got ESTOP and ENABLE 0: its next SIPs say so, and the wheels stop.
  cycles(15);
  CHECK_FALSE(client.state().motors_enabled);
  CHECK(std::fabs(client.state().trans_vel_mps) < 0.01);
  CHECK(robot.state().link == hal::LinkState::safety_stop);
  CHECK(robot.state().why_stopped.find("e-stop pressed") != std::string::npos);
  CHECK_FALSE(robot.set_velocity(0.3, 0.0));

  nodes.command("estop off");
  for (int i = 0; i < 10 && !robot.verdict().clear; ++i) cycles(1);
  REQUIRE_MESSAGE(robot.rearm(), robot.verdict().why);
  REQUIRE(robot.set_velocity(0.2, 0.0));
  cycles(10);
  CHECK(client.state().motors_enabled);
  CHECK(client.state().trans_vel_mps > 0.1);
  CHECK(client.disconnect());
  CHECK(nodes.quit() == 0);
}
