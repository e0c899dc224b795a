#include <doctest/doctest.h>

#include <memory>
#include <string>

#include "ticking_drive_base.hpp"
#include "p3at/bridge/accessories/guarded_drive_base.hpp"
#include "p3at/sim/can/sim_accessories.hpp"
#include "p3at/sim/can/sim_can_network.hpp"
#include "p3at/sim/sim_clock.hpp"

namespace bridge = p3at::bridge;
namespace hal = p3at::hal;
namespace sim = p3at::sim;

namespace {

constexpr std::int64_t kCycleUs = 100'000;

// Fast-time rig: the fake drive base's clock ticks step the simulated accessories.
struct Rig {
  sim::SimClock clock;
  sim::SimCanNetwork net{clock};
  std::unique_ptr<hal::CanBus> hub_bus = net.attach("bridge");
  std::unique_ptr<hal::CanBus> node_bus = net.attach("nodes");
  sim::SimAccessories nodes{*node_bus, sim::SimGyroConfig{}, sim::SimSafetyNodeConfig{}};
  bridge::AccessoryHub hub{*hub_bus};
  p3at::test::TickingDriveBase base{clock, kCycleUs};
  bridge::GuardedDriveBase guarded{base, hub, clock, [this] { return base.enable_motors(); },
                                   bridge::GuardConfig{10, true, false, "safety"}};
  double true_rate_radps = 0.0;
  int node_send_failures = 0;  // while the bus is off the nodes cannot send

  Rig() {
    base.on_tick = [this](std::int64_t now_us) {
      if (!nodes.step(now_us, true_rate_radps)) ++node_send_failures;
    };
    REQUIRE(hub.start());
  }

  void cycles(int n) {
    for (int i = 0; i < n; ++i) {
      auto got = guarded.wait_for_update(200);
      REQUIRE(got);
      REQUIRE(*got);
    }
  }
};

}  // namespace

TEST_CASE("motion is refused until the safety node is clear and the executive arms") {
  Rig rig;
  auto refused = rig.guarded.set_velocity(0.3, 0.0);
  REQUIRE_FALSE(refused);
  CHECK(refused.error().code == p3at::Error::Code::state);
  CHECK(refused.error().message.find("safety latch") != std::string::npos);
  CHECK(rig.guarded.state().link == hal::LinkState::safety_stop);
  CHECK_FALSE(rig.guarded.state().why_stopped.empty());
  CHECK(rig.base.set_velocity_calls == 0);

  rig.cycles(5);  // nodes boot, get started, report clear
  CHECK(rig.guarded.verdict().clear);
  REQUIRE(rig.guarded.rearm());
  CHECK(rig.base.enable_calls == 1);
  CHECK(rig.guarded.state().link == hal::LinkState::ok);
  REQUIRE(rig.guarded.set_velocity(0.3, 0.0));
  CHECK(rig.base.trans_mps() == 0.3);
}

TEST_CASE("an injected e-stop stops the robot within one control cycle") {
  Rig rig;
  rig.cycles(5);
  REQUIRE(rig.guarded.rearm());
  REQUIRE(rig.guarded.set_velocity(0.4, 0.2));
  rig.cycles(3);

  // Press in the middle of a cycle: between two SIPs.
  rig.clock.advance_us(37'000);
  const std::int64_t pressed_us = rig.clock.now_us();
  rig.nodes.safety().press_estop(true);
  auto got = rig.guarded.wait_for_update(200);
  REQUIRE(got);
  REQUIRE(rig.base.estop_times_us.size() == 1);
  const std::int64_t latency_us = rig.base.estop_times_us[0] - pressed_us;
  CAPTURE(latency_us);
  CHECK(latency_us >= 0);
  CHECK(latency_us < kCycleUs);
  CHECK(rig.base.trans_mps() == 0.0);
  CHECK(rig.base.estop_latched());
  CHECK(rig.guarded.state().link == hal::LinkState::safety_stop);
  CHECK(rig.guarded.state().why_stopped.find("e-stop pressed on safety node 17") != std::string::npos);
  CHECK_FALSE(rig.guarded.set_velocity(0.1, 0.0));

  // Released: still latched until re-armed; re-arming while pressed is refused.
  rig.cycles(2);
  auto early = rig.guarded.rearm();
  REQUIRE_FALSE(early);
  CHECK(early.error().message.find("e-stop pressed") != std::string::npos);
  rig.nodes.safety().press_estop(false);
  rig.cycles(2);
  CHECK(rig.guarded.verdict().clear);
  CHECK_FALSE(rig.guarded.verdict().motion_allowed);
  CHECK_FALSE(rig.guarded.set_velocity(0.1, 0.0));
  REQUIRE(rig.guarded.rearm());
  REQUIRE(rig.guarded.set_velocity(0.1, 0.0));
  CHECK(rig.base.estop_times_us.size() == 1);  // one trip, one emergency stop
}

TEST_CASE("a silent safety node stops the robot within three heartbeat periods plus one cycle") {
  Rig rig;
  rig.cycles(5);
  REQUIRE(rig.guarded.rearm());
  const std::int64_t silent_us = rig.clock.now_us();
  rig.nodes.safety().set_silent(true);
  rig.cycles(6);
  REQUIRE(rig.base.estop_times_us.size() == 1);
  const std::int64_t after_us = rig.base.estop_times_us[0] - silent_us;
  CAPTURE(after_us);
  // Its state messages (50 ms) go stale first: 150 ms; its heartbeat after 300 ms.
  CHECK(after_us <= 3 * 100'000 + kCycleUs);
  CHECK(rig.guarded.state().why_stopped.find("safety node 17") != std::string::npos);
}

TEST_CASE("a bumper hit and a bus-off both stop; recovery needs a re-arm") {
  Rig rig;
  rig.cycles(5);
  REQUIRE(rig.guarded.rearm());
  rig.nodes.safety().set_bumpers(0x01);
  rig.cycles(1);
  CHECK(rig.base.estop_times_us.size() == 1);
  CHECK(rig.guarded.state().why_stopped.find("bumper hit") != std::string::npos);
  rig.nodes.safety().set_bumpers(0);
  rig.cycles(1);
  REQUIRE(rig.guarded.rearm());

  rig.net.set_state(hal::CanBusState::bus_off, "injected");
  rig.cycles(1);
  CHECK(rig.node_send_failures > 0);
  CHECK(rig.base.estop_times_us.size() == 2);
  CHECK(rig.guarded.state().why_stopped.find("CAN bus bus-off") != std::string::npos);
  CHECK_FALSE(rig.guarded.rearm());
  rig.net.set_state(hal::CanBusState::error_active, "restarted");
  rig.cycles(2);
  REQUIRE(rig.guarded.rearm());
  CHECK(rig.guarded.state().link == hal::LinkState::ok);
}

TEST_CASE("the guarded state's heading is gyro-aided") {
  Rig rig;
  rig.base.odom_turn_scale_error = 0.25;  // skid: odometry over-reports turns by 25 %
  rig.cycles(30);                          // 3 s standing still: the bias is learned
  REQUIRE(rig.guarded.rearm());
  REQUIRE(rig.guarded.set_velocity(0.0, 0.5));
  rig.true_rate_radps = 0.5;
  rig.cycles(40);
  REQUIRE(rig.guarded.set_velocity(0.0, 0.0));
  rig.true_rate_radps = 0.0;
  rig.cycles(5);
  const double truth = rig.base.true_heading_rad();
  const double odom = rig.base.state().odometry.theta_rad;
  const double aided = rig.guarded.state().odometry.theta_rad;
  CAPTURE(truth);
  CAPTURE(odom);
  CAPTURE(aided);
  CHECK(std::fabs(odom - truth) > 0.4);
  CHECK(std::fabs(aided - truth) < 0.03);
}

TEST_CASE("re-arming when the motors cannot be re-enabled fails, naming the motors, and motion stays refused") {
  Rig rig;
  rig.cycles(5);
  REQUIRE(rig.guarded.rearm());
  rig.nodes.safety().set_bumpers(0x01);
  rig.cycles(1);
  REQUIRE(rig.base.estop_latched());
  rig.nodes.safety().set_bumpers(0);
  rig.cycles(1);
  // What ArcosClient::enable_motors(true) returns after five lost ENABLEs.
  rig.base.enable_failure = "tcp://robot: motors stayed off after 5 ENABLE commands, 3 SIPs apart (ENABLE lost?)";
  const auto failed = rig.guarded.rearm();
  REQUIRE_FALSE(failed);
  CHECK(failed.error().message.find("motors not re-enabled: ") == 0);
  CHECK(failed.error().message.find("ENABLE lost?") != std::string::npos);
  CHECK_FALSE(rig.guarded.set_velocity(0.1, 0.0));
  CHECK(rig.base.trans_mps() == 0.0);
  rig.base.enable_failure.clear();
  REQUIRE(rig.guarded.rearm());
  REQUIRE(rig.guarded.set_velocity(0.1, 0.0));
}
