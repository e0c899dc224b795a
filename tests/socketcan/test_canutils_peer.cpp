// can-utils as an independent peer on a real kernel: frames our encoders send
// through the SocketCAN backend are read back from `candump -L` and decoded;
// frames injected with `cansend` are decoded by our backend and the accessory
// hub, and an e-stop injected with cansend stops a drive base within one cycle.
#include <doctest/doctest.h>

#include <signal.h>

#include <sstream>
#include <string>
#include <vector>

#include "bus_helpers.hpp"
#include "can_test_env.hpp"
#include "p3at/bridge/accessories/accessory_hub.hpp"
#include "p3at/bridge/accessories/guarded_drive_base.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/protocols/can/accessories.hpp"
#include "p3at/protocols/can/canopen.hpp"
#include "ticking_drive_base.hpp"

namespace bridge = p3at::bridge;
namespace can = p3at::can;
namespace hal = p3at::hal;
using p3at::test::can_interface;
using p3at::test::can_url;
using p3at::test::shell;

namespace {

std::unique_ptr<hal::CanBus> open_bus(const std::string& url) {
  auto bus = hal::open_can_bus(url);
  REQUIRE_MESSAGE(bus, (bus ? "" : bus.error().message));
  return std::move(*bus);
}

// The frames of `candump -L` lines: "(1700000000.123456) vcan0 190#40420F00B80B0700".
std::vector<can::Frame> candump_frames(const std::string& log) {
  std::vector<can::Frame> frames;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string stamp, iface, text;
    if (!(words >> stamp >> iface >> text) || iface != can_interface()) continue;
    auto frame = can::parse_frame(text);
    REQUIRE_MESSAGE(frame, "candump printed '" << line << "'");
    frames.push_back(*frame);
  }
  return frames;
}

void cansend(const std::string& frame) { REQUIRE(shell("cansend " + can_interface() + " " + frame) == 0); }

}  // namespace

TEST_CASE("frames we encode and send are decoded from candump's output") {
  auto bus = open_bus(can_url());
  p3at::test::Child candump({"candump", "-L", can_interface()});
  // candump is ready once it prints a marker frame we keep sending.
  const can::Frame marker = *can::parse_frame("7FE#AA");
  bool ready = false;
  for (int i = 0; i < 200 && !ready; ++i) {
    REQUIRE(bus->send(marker));
    ready = candump.wait_for_log("7FE#AA", 0.02);
  }
  REQUIRE(ready);

  can::GyroSample gyro;
  gyro.yaw_rate_radps = -0.25;
  gyro.temperature_c = 36.5;
  gyro.counter = 200;
  can::SafetyState safety;
  safety.estop_pressed = true;
  safety.bumpers = 0x30;
  safety.counter = 9;
  can::Emergency emcy;
  emcy.error_code = can::emcy_code::kDeviceTemperature;
  emcy.error_register = can::error_register::kTemperature;
  const std::vector<can::Frame> sent{*can::encode_nmt(can::NmtCommand::start, 0),
                                     can::encode_heartbeat(0x11, can::NmtState::operational),
                                     can::encode_gyro_pdo(0x10, gyro), can::encode_safety_pdo(0x11, safety),
                                     can::encode_emcy(0x10, emcy)};
  for (const auto& f : sent) REQUIRE(bus->send(f));
  REQUIRE(candump.wait_for_log("090#", 3.0));  // the EMCY, last
  candump.signal(SIGINT);
  candump.wait_exit(3.0);

  std::vector<can::Frame> dumped;
  for (const auto& f : candump_frames(candump.log())) {
    if (!(f == marker)) dumped.push_back(f);
  }
  REQUIRE(dumped.size() == sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) CHECK(dumped[i] == sent[i]);
  auto nmt = can::decode_nmt(dumped[0]);
  REQUIRE(nmt);
  CHECK(nmt->command == can::NmtCommand::start);
  auto g = can::decode_gyro_pdo(dumped[2]);
  REQUIRE(g);
  CHECK(g->yaw_rate_radps == doctest::Approx(-0.25));
  CHECK(g->temperature_c == doctest::Approx(36.5));
  CHECK(g->counter == 200);
  auto s = can::decode_safety_pdo(dumped[3]);
  REQUIRE(s);
  CHECK(s->estop_pressed);
  CHECK(s->bumpers == 0x30);
  auto e = can::decode_emcy(dumped[4]);
  REQUIRE(e);
  CHECK(e->error_code == 0x4200);
}

TEST_CASE("frames injected with cansend are decoded by us") {
  auto bus = open_bus(can_url());
  p3at::test::drain(*bus);
  cansend("190#40420F00B80B0700");  // gyro: 1 rad/s, 30 °C, counter 7
  cansend("191#010005FB");          // safety: e-stop, counter 5
  cansend("091#01FF800000000000");  // EMCY 0xFF01 from node 0x11
  cansend("711#05");                // heartbeat operational
  auto g = p3at::test::receive_within(*bus, 2000);
  REQUIRE(g);
  auto gyro = can::decode_gyro_pdo(g->frame);
  REQUIRE(gyro);
  CHECK(gyro->yaw_rate_radps == doctest::Approx(1.0));
  CHECK(gyro->temperature_c == doctest::Approx(30.0));
  CHECK(gyro->counter == 7);
  auto s = p3at::test::receive_within(*bus, 2000);
  REQUIRE(s);
  auto safety = can::decode_safety_pdo(s->frame);
  REQUIRE(safety);
  CHECK(safety->estop_pressed);
  CHECK(safety->counter == 5);
  auto e = p3at::test::receive_within(*bus, 2000);
  REQUIRE(e);
  auto emcy = can::decode_emcy(e->frame);
  REQUIRE(emcy);
  CHECK(emcy->error_code == 0xFF01);
  CHECK(can::classify(e->frame).node_id == 0x11);
  auto h = p3at::test::receive_within(*bus, 2000);
  REQUIRE(h);
  auto hb = can::decode_heartbeat(h->frame);
  REQUIRE(hb);
  CHECK(*hb == can::NmtState::operational);
}

TEST_CASE("the hub counts and ignores cansend garbage") {
  auto bus = open_bus(can_url());
  p3at::test::drain(*bus);
  bridge::AccessoryHub hub(*bus);
  for (const char* f : {"123#00", "190#0102", "711#0505", "191#00000000", "190#40420F00B80B0700",
                        "190#40420F00B80B0700", "00000191#00"}) {
    cansend(f);
  }
  hal::SteadyClock clock;
  const std::int64_t deadline = clock.now_us() + 3'000'000;
  while (hub.counters().frames < 7 && clock.now_us() < deadline) {
    hub.poll(clock.now_us());
    REQUIRE(bus->wait(10));
  }
  const auto& c = hub.counters();
  CHECK(c.frames == 7);
  CHECK(c.unknown_id == 2);
  CHECK(c.wrong_length == 2);
  CHECK(c.bad_payload == 1);
  CHECK(c.stale_counter == 1);
  CHECK(c.gyro_samples == 1);
}

TEST_CASE("an e-stop injected with cansend stops the robot within one control cycle") {
  auto bus = open_bus(can_url());
  p3at::test::drain(*bus);
  hal::SteadyClock clock;
  // cansend plays the node, one process per frame: give it seconds, not the
  // node's real 100 ms / 50 ms periods, so only the e-stop can trip the latch.
  bridge::AccessoryConfig config;
  config.safety = bridge::SafetyMonitorConfig{2'000'000, 3, 2'000'000, 3};
  bridge::AccessoryHub hub(*bus, config);
  p3at::test::TickingDriveBase base(clock, 100'000);
  bridge::GuardedDriveBase guarded(base, hub, clock, [&] { return base.enable_motors(); },
                                   bridge::GuardConfig{10, false, true, "safety"});
  // The node, played by cansend: operational and clear.
  cansend("711#05");
  cansend("191#000001FE");
  REQUIRE(guarded.wait_for_update(200));
  REQUIRE_MESSAGE(guarded.rearm(), guarded.verdict().why);
  REQUIRE(guarded.set_velocity(0.3, 0.0));

  cansend("191#010002FC");  // e-stop pressed, counter 2
  std::int64_t deadline = clock.now_us() + 1'000'000;
  while (base.estop_times_us.empty() && clock.now_us() < deadline) REQUIRE(guarded.wait_for_update(200));
  REQUIRE(base.estop_times_us.size() == 1);
  // From the e-stop frame's arrival (kernel timestamp) to the emergency stop.
  const std::int64_t latency_us = base.estop_times_us[0] - hub.safety().last_trip().state_stamp_us;
  CAPTURE(latency_us);
  CHECK(latency_us >= 0);
  CHECK(latency_us < 100'000);
  CHECK(guarded.state().link == hal::LinkState::safety_stop);
  CHECK(guarded.state().why_stopped.find("e-stop pressed") != std::string::npos);
  CHECK_FALSE(guarded.set_velocity(0.3, 0.0));
}
