#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "p3at/protocols/can/accessories.hpp"
#include "p3at/sim/can/sim_accessories.hpp"
#include "p3at/sim/can/sim_can_network.hpp"
#include "p3at/sim/sim_clock.hpp"

namespace can = p3at::can;
namespace hal = p3at::hal;
namespace sim = p3at::sim;

namespace {

std::vector<hal::CanRxFrame> drain(hal::CanBus& bus) {
  std::vector<hal::CanRxFrame> out;
  for (;;) {
    auto rx = bus.receive();
    REQUIRE(rx);
    if (!rx->has_value()) return out;
    out.push_back(**rx);
  }
}

void send_nmt_start(hal::CanBus& bus) {
  auto f = can::encode_nmt(can::NmtCommand::start, 0);
  REQUIRE(f);
  REQUIRE(bus.send(*f));
}

}  // namespace

TEST_CASE("sim network delivers to every other endpoint, stamped, filtered") {
  sim::SimClock clock(5'000);
  sim::SimCanNetwork net(clock);
  auto a = net.attach("a");
  auto b = net.attach("b");
  auto c = net.attach("c");
  CHECK(a->describe() == "sim-can://a");
  const hal::CanFilter only_heartbeats{0x700, 0x780, false};
  REQUIRE(c->set_filters({&only_heartbeats, 1}));

  REQUIRE(a->send(can::encode_heartbeat(0x11, can::NmtState::operational)));
  clock.advance_us(100);
  REQUIRE(a->send(can::encode_safety_pdo(0x11, can::SafetyState{})));
  auto at_a = drain(*a);
  auto at_b = drain(*b);
  auto at_c = drain(*c);
  CHECK(at_a.empty());  // no echo to the sender
  REQUIRE(at_b.size() == 2);
  CHECK(at_b[0].stamp_us == 5'000);
  CHECK(at_b[1].stamp_us == 5'100);
  CHECK(can::classify(at_b[1].frame).kind == can::MessageKind::tpdo1);
  REQUIRE(at_c.size() == 1);
  CHECK(can::classify(at_c[0].frame).kind == can::MessageKind::heartbeat);
  CHECK(a->status().frames_sent == 2);
  CHECK(b->status().frames_received == 2);
  CHECK_FALSE(*b->wait(0));
}

TEST_CASE("sim network bus-off stops traffic and recovery is counted") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto a = net.attach("a");
  auto b = net.attach("b");
  net.set_state(hal::CanBusState::bus_off, "test");
  auto refused = a->send(can::encode_heartbeat(0x10, can::NmtState::operational));
  REQUIRE_FALSE(refused);
  CHECK(refused.error().code == p3at::Error::Code::state);
  CHECK(b->status().state == hal::CanBusState::bus_off);
  CHECK(b->status().bus_off_events == 1);
  CHECK(a->status().send_failures == 1);
  net.set_state(hal::CanBusState::error_active, "restarted");
  REQUIRE(a->send(can::encode_heartbeat(0x10, can::NmtState::operational)));
  CHECK(drain(*b).size() == 1);
  CHECK(b->status().recoveries == 1);
  CHECK(b->status().last_error.find("bus-off -> error-active") != std::string::npos);
}

TEST_CASE("sim nodes boot, wait for NMT start, then send at their rates") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto master = net.attach("master");
  auto node_bus = net.attach("nodes");
  sim::SimAccessories nodes(*node_bus, sim::SimGyroConfig{}, sim::SimSafetyNodeConfig{});

  REQUIRE(nodes.step(clock.now_us(), 0.0));
  auto boot = drain(*master);
  REQUIRE(boot.size() == 2);
  CHECK(can::format_frame(boot[0].frame) == "710#00");
  CHECK(can::format_frame(boot[1].frame) == "711#00");

  // Pre-operational: heartbeats only, no PDOs.
  for (int ms = 1; ms <= 300; ++ms) {
    clock.advance_us(1000);
    REQUIRE(nodes.step(clock.now_us(), 0.0));
  }
  for (const auto& rx : drain(*master)) CHECK(can::classify(rx.frame).kind == can::MessageKind::heartbeat);
  CHECK(nodes.gyro().samples_sent() == 0);

  send_nmt_start(*master);
  int gyro_pdos = 0;
  int safety_pdos = 0;
  int heartbeats = 0;
  for (int ms = 1; ms <= 1000; ++ms) {
    clock.advance_us(1000);
    REQUIRE(nodes.step(clock.now_us(), 0.0));
    for (const auto& rx : drain(*master)) {
      const auto cob = can::classify(rx.frame);
      if (cob.kind == can::MessageKind::tpdo1 && cob.node_id == can::kDefaultGyroNodeId) ++gyro_pdos;
      if (cob.kind == can::MessageKind::tpdo1 && cob.node_id == can::kDefaultSafetyNodeId) ++safety_pdos;
      if (cob.kind == can::MessageKind::heartbeat) {
        ++heartbeats;
        CHECK(rx.frame.data[0] == 0x05);
      }
    }
  }
  CHECK(gyro_pdos == doctest::Approx(100).epsilon(0.02));  // 100 Hz
  CHECK(safety_pdos == doctest::Approx(20).epsilon(0.06));  // 20 Hz
  CHECK(heartbeats == doctest::Approx(20).epsilon(0.06));  // 2 nodes × 10 Hz
}

TEST_CASE("sim gyro measures with its bias, scale error and noise") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto master = net.attach("master");
  auto node_bus = net.attach("gyro");
  sim::SimGyroConfig cfg;
  cfg.bias_radps = 0.02;
  cfg.scale_error = 0.05;
  cfg.noise_sd_radps = 0.01;
  cfg.auto_start = true;
  cfg.seed = 7;
  sim::SimAccessories nodes(*node_bus, cfg, sim::SimSafetyNodeConfig{}, true, false);
  const double true_rate = 0.5;
  double sum = 0.0;
  double sum_sq = 0.0;
  int n = 0;
  std::uint8_t expected_counter = 0;
  for (int ms = 0; ms < 20'000; ++ms) {
    REQUIRE(nodes.step(clock.now_us(), true_rate));
    for (const auto& rx : drain(*master)) {
      if (can::classify(rx.frame).kind != can::MessageKind::tpdo1) continue;
      auto s = can::decode_gyro_pdo(rx.frame);
      REQUIRE(s);
      CHECK(s->counter == expected_counter);
      ++expected_counter;
      sum += s->yaw_rate_radps;
      sum_sq += s->yaw_rate_radps * s->yaw_rate_radps;
      ++n;
    }
    clock.advance_us(1000);
  }
  REQUIRE(n > 1900);
  const double mean = sum / n;
  const double sd = std::sqrt(sum_sq / n - mean * mean);
  CHECK(mean == doctest::Approx(1.05 * true_rate + 0.02).epsilon(0.002));
  CHECK(sd == doctest::Approx(0.01).epsilon(0.1));
}

TEST_CASE("sim safety node reports changes at once, EMCY on fault, silence on request") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto master = net.attach("master");
  auto node_bus = net.attach("safety");
  sim::SimSafetyNodeConfig cfg;
  cfg.auto_start = true;
  sim::SimAccessories nodes(*node_bus, sim::SimGyroConfig{}, cfg, false, true);
  REQUIRE(nodes.step(0, 0.0));
  clock.advance_us(1000);
  REQUIRE(nodes.step(clock.now_us(), 0.0));
  drain(*master);

  clock.advance_us(1000);
  nodes.safety().press_estop(true);
  REQUIRE(nodes.step(clock.now_us(), 0.0));
  auto rx = drain(*master);
  REQUIRE(rx.size() == 1);  // sent on change, not 50 ms later
  auto s = can::decode_safety_pdo(rx[0].frame);
  REQUIRE(s);
  CHECK(s->estop_pressed);

  nodes.safety().set_fault(true);
  clock.advance_us(1000);
  REQUIRE(nodes.step(clock.now_us(), 0.0));
  rx = drain(*master);
  REQUIRE(rx.size() == 2);
  auto emcy = can::decode_emcy(rx[0].frame);
  REQUIRE(emcy);
  CHECK(emcy->error_code == can::emcy_code::kEstopCircuit);

  nodes.safety().set_silent(true);
  for (int ms = 0; ms < 500; ++ms) {
    clock.advance_us(1000);
    REQUIRE(nodes.step(clock.now_us(), 0.0));
  }
  CHECK(drain(*master).empty());
}

TEST_CASE("sim nodes obey NMT stop and reset") {
  sim::SimClock clock;
  sim::SimCanNetwork net(clock);
  auto master = net.attach("master");
  auto node_bus = net.attach("nodes");
  sim::SimGyroConfig g;
  g.auto_start = true;
  sim::SimAccessories nodes(*node_bus, g, sim::SimSafetyNodeConfig{}, true, false);
  for (int ms = 0; ms < 100; ++ms, clock.advance_us(1000)) REQUIRE(nodes.step(clock.now_us(), 0.0));
  const auto before = nodes.gyro().samples_sent();
  CHECK(before >= 9);
  auto stop = can::encode_nmt(can::NmtCommand::stop, can::kDefaultGyroNodeId);
  REQUIRE(stop);
  REQUIRE(master->send(*stop));
  for (int ms = 0; ms < 300; ++ms, clock.advance_us(1000)) REQUIRE(nodes.step(clock.now_us(), 0.0));
  CHECK(nodes.gyro().samples_sent() == before);
  CHECK(nodes.gyro().node().state() == can::NmtState::stopped);

  auto reset = can::encode_nmt(can::NmtCommand::reset_node, 0);
  REQUIRE(reset);
  drain(*master);
  REQUIRE(master->send(*reset));
  REQUIRE(nodes.step(clock.now_us(), 0.0));
  auto rx = drain(*master);
  REQUIRE_FALSE(rx.empty());
  CHECK(can::format_frame(rx[0].frame) == "710#00");  // boot-up again
}
