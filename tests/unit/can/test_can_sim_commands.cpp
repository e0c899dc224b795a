#include <doctest/doctest.h>

#include <memory>

#include "p3at/sim/can/node_commands.hpp"
#include "p3at/sim/can/sim_can_network.hpp"
#include "p3at/sim/sim_clock.hpp"

namespace sim = p3at::sim;
using p3at::can_sim::apply_command;

TEST_CASE("p3at_can_sim commands change the simulated nodes") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto bus = net.attach("nodes");
  sim::SimAccessories nodes(*bus, sim::SimGyroConfig{}, sim::SimSafetyNodeConfig{});

  REQUIRE(apply_command("estop on", nodes));
  CHECK(nodes.safety().state().estop_pressed);
  REQUIRE(apply_command("  estop   off  ", nodes));
  CHECK_FALSE(nodes.safety().state().estop_pressed);
  REQUIRE(apply_command("bumpers 0x21", nodes));
  CHECK(nodes.safety().state().bumpers == 0x21);
  REQUIRE(apply_command("fault 1", nodes));
  CHECK(nodes.safety().state().fault);
  REQUIRE(apply_command("silent on", nodes));
  CHECK(nodes.safety().node().silent());
  REQUIRE(apply_command("gyro-silent on", nodes));
  CHECK(nodes.gyro().node().silent());
  auto rate = apply_command("rate -0.25", nodes);
  REQUIRE(rate);
  CHECK(rate->has_rate);
  CHECK(rate->rate_radps == -0.25);
  auto quit = apply_command("quit", nodes);
  REQUIRE(quit);
  CHECK(quit->quit);
  auto blank = apply_command("# a comment", nodes);
  REQUIRE(blank);
  CHECK_FALSE(blank->quit);
  CHECK_FALSE(blank->has_rate);
}

TEST_CASE("p3at_can_sim rejects malformed commands with a clear message") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto bus = net.attach("nodes");
  sim::SimAccessories nodes(*bus, sim::SimGyroConfig{}, sim::SimSafetyNodeConfig{});
  for (const char* bad : {"estop", "estop maybe", "bumpers", "bumpers 256", "bumpers -1", "bumpers x", "rate",
                          "rate fast", "rate 1e999", "rate nan", "launch", "silent on off"}) {
    CAPTURE(bad);
    auto r = apply_command(bad, nodes);
    REQUIRE_FALSE(r);
    CHECK(r.error().code == p3at::Error::Code::invalid_argument);
    CHECK(r.error().message.find(std::string("command '") + bad + "'") == 0);
  }
  CHECK_FALSE(nodes.safety().state().estop_pressed);
}
