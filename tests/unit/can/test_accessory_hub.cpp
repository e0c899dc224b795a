#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "p3at/bridge/accessories/accessory_hub.hpp"
#include "p3at/sim/can/sim_accessories.hpp"
#include "p3at/sim/can/sim_can_network.hpp"
#include "p3at/sim/sim_clock.hpp"

namespace can = p3at::can;
namespace hal = p3at::hal;
namespace sim = p3at::sim;
using p3at::bridge::AccessoryHub;

namespace {

can::Frame frame_of(const char* text) {
  auto f = can::parse_frame(text);
  REQUIRE(f);
  return *f;
}

struct Rig {
  sim::SimClock clock;
  sim::SimCanNetwork net{clock};
  std::unique_ptr<hal::CanBus> hub_bus = net.attach("bridge");
  std::unique_ptr<hal::CanBus> node_bus = net.attach("nodes");
  std::unique_ptr<hal::CanBus> tool = net.attach("tool");  // an independent sender
  AccessoryHub hub{*hub_bus};

  void inject(const char* text) { REQUIRE(tool->send(frame_of(text))); }
};

}  // namespace

TEST_CASE("unknown ids, wrong lengths, stale counters and bad payloads are counted and ignored") {
  Rig rig;
  rig.inject("123#00");                    // no node of ours
  rig.inject("00000190#40420F00B80B0700"); // extended id
  rig.inject("190#40420F00B80B07");        // gyro PDO, 7 bytes
  rig.inject("711#0500");                  // heartbeat, 2 bytes
  rig.inject("091#01FF");                  // EMCY, 2 bytes
  rig.inject("191#00000000");              // safety PDO, bad check byte
  rig.inject("711#06");                    // unknown NMT state
  rig.inject("190#40420F00B80B0700");      // gyro counter 7
  rig.inject("190#40420F00B80B0700");      // repeated
  rig.inject("190#40420F00B80B0600");      // behind
  rig.inject("191#000003FC");              // safety counter 3
  rig.inject("191#000003FC");              // repeated
  rig.inject("000#0100");                  // NMT from another master
  rig.hub.poll(rig.clock.now_us());
  const auto& c = rig.hub.counters();
  CHECK(c.frames == 13);
  CHECK(c.unknown_id == 2);
  CHECK(c.wrong_length == 3);
  CHECK(c.bad_payload == 2);
  CHECK(c.stale_counter == 3);
  CHECK(c.ignored == 1);
  CHECK(c.gyro_samples == 1);
  CHECK(c.safety_states == 1);
  CHECK(rig.hub.gyro().samples() == 1);
  CHECK(rig.hub.gyro().heading_rad() == doctest::Approx(0.01));  // only the one good sample
}

TEST_CASE("the hub starts booting nodes with NMT and tracks lost gyro samples") {
  Rig rig;
  rig.inject("710#00");  // gyro boot-up
  rig.hub.poll(0);
  CHECK(rig.hub.counters().nmt_sent == 1);
  bool start_seen = false;
  for (;;) {
    auto rx = rig.node_bus->receive();
    REQUIRE(rx);
    if (!rx->has_value()) break;
    start_seen = start_seen || can::format_frame((*rx)->frame) == "000#0110";
  }
  CHECK(start_seen);
  rig.inject("710#7F");  // still pre-operational in the same heartbeat period: no second start yet
  rig.hub.poll(50'000);
  CHECK(rig.hub.counters().nmt_sent == 1);
  rig.inject("710#7F");
  rig.hub.poll(150'000);
  CHECK(rig.hub.counters().nmt_sent == 2);

  rig.inject("190#000000000000" "0100");  // counter 1
  rig.inject("190#000000000000" "0500");  // counter 5: three lost
  rig.hub.poll(160'000);
  CHECK(rig.hub.counters().gyro_lost_samples == 3);
}

TEST_CASE("end to end in fast time: nodes started, bias learned, turn measured, e-stop trips") {
  Rig rig;
  sim::SimGyroConfig g;
  g.bias_radps = 0.01;
  g.noise_sd_radps = 0.002;
  g.scale_error = 0.0;
  sim::SimAccessories nodes(*rig.node_bus, g, sim::SimSafetyNodeConfig{});
  REQUIRE(rig.hub.start());

  hal::Pose2 odom{};
  double true_rate = 0.0;
  double truth = 0.0;
  auto run_ms = [&](int ms, bool still) {
    for (int i = 0; i < ms; ++i) {
      rig.clock.advance_us(1000);
      truth += true_rate * 1e-3;
      odom.theta_rad += 1.2 * true_rate * 1e-3;  // odometry over-reports turns by 20 %
      REQUIRE(nodes.step(rig.clock.now_us(), true_rate));
      if (rig.clock.now_us() % 10'000 == 0) rig.hub.poll(rig.clock.now_us());
      if (rig.clock.now_us() % 100'000 == 0) {
        rig.hub.set_standstill(still, rig.clock.now_us());
        rig.hub.aided_pose(odom, rig.clock.now_us());
      }
    }
  };
  run_ms(3000, true);
  CHECK(rig.hub.gyro_usable(rig.clock.now_us()));
  CHECK(rig.hub.gyro().bias_radps() == doctest::Approx(0.01).epsilon(0.05));
  REQUIRE(rig.hub.rearm(rig.clock.now_us()));
  CHECK(rig.hub.poll(rig.clock.now_us()).motion_allowed);

  true_rate = 0.5;
  run_ms(4000, false);
  true_rate = 0.0;
  run_ms(1000, true);
  CHECK(truth == doctest::Approx(2.0));
  CHECK(odom.theta_rad == doctest::Approx(2.4));
  CHECK(rig.hub.fuser().pose().theta_rad == doctest::Approx(truth).epsilon(0.01));

  nodes.safety().press_estop(true);
  run_ms(1, true);
  const auto v = rig.hub.poll(rig.clock.now_us());
  CHECK(v.stop_now);
  CHECK(v.why.find("e-stop") != std::string::npos);
  const auto& c = rig.hub.counters();
  CHECK(c.unknown_id == 0);
  CHECK(c.stale_counter == 0);
  CHECK(c.gyro_lost_samples == 0);
  CHECK(c.gyro_samples > 790);
}

TEST_CASE("a gyro fault or silence takes the gyro out of the fusion") {
  Rig rig;
  sim::SimGyroConfig g;
  g.auto_start = true;
  sim::SimSafetyNodeConfig s;
  s.auto_start = true;
  sim::SimAccessories nodes(*rig.node_bus, g, s);
  for (int ms = 1; ms <= 2000; ++ms) {
    rig.clock.advance_us(1000);
    REQUIRE(nodes.step(rig.clock.now_us(), 0.0));
    rig.hub.poll(rig.clock.now_us());
    if (ms % 100 == 0) rig.hub.set_standstill(true, rig.clock.now_us());
  }
  REQUIRE(rig.hub.gyro_usable(rig.clock.now_us()));
  nodes.gyro().set_fault(true);
  for (int ms = 0; ms < 20; ++ms) {
    rig.clock.advance_us(1000);
    REQUIRE(nodes.step(rig.clock.now_us(), 0.0));
  }
  rig.hub.poll(rig.clock.now_us());
  CHECK(rig.hub.gyro_problem(rig.clock.now_us()) == "gyro reports a sensor fault");
  nodes.gyro().set_fault(false);
  nodes.gyro().set_silent(true);
  for (int ms = 0; ms < 100; ++ms) {
    rig.clock.advance_us(1000);
    REQUIRE(nodes.step(rig.clock.now_us(), 0.0));
    rig.hub.poll(rig.clock.now_us());
  }
  CHECK(rig.hub.gyro_problem(rig.clock.now_us()).find("gyro silent for") == 0);
  CHECK(rig.hub.counters().emergencies >= 1);
}

TEST_CASE("the standstill test reads the drive state") {
  hal::DriveState s;
  CHECK(AccessoryHub::is_standstill(s));
  s.rot_vel_radps = 0.1;
  CHECK_FALSE(AccessoryHub::is_standstill(s));
  s.rot_vel_radps = 0.0;
  s.moving = true;
  CHECK_FALSE(AccessoryHub::is_standstill(s));
}
