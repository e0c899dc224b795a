#include <doctest/doctest.h>

#include <string>

#include "p3at/bridge/accessories/safety_monitor.hpp"

using p3at::bridge::SafetyMonitor;
using p3at::bridge::SafetyVerdict;
namespace can = p3at::can;
namespace hal = p3at::hal;

namespace {

constexpr std::uint8_t kNode = 0x11;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A node that reports clear and operational at `t_us`.
void healthy(SafetyMonitor& m, std::int64_t t_us) {
  m.on_heartbeat(can::NmtState::operational, t_us);
  can::SafetyState s;
  m.on_state(s, t_us);
}

}  // namespace

TEST_CASE("the monitor starts disarmed and arms only when the node is clear") {
  SafetyMonitor m(kNode);
  SafetyVerdict v = m.evaluate(0);
  CHECK_FALSE(v.motion_allowed);
  CHECK_FALSE(v.stop_now);
  CHECK_FALSE(v.clear);
  CHECK(contains(v.why, "not armed yet"));
  auto refused = m.rearm(0);
  REQUIRE_FALSE(refused);
  CHECK(refused.error().code == p3at::Error::Code::state);
  CHECK(contains(refused.error().message, "no heartbeat from safety node 17"));

  healthy(m, 1000);
  v = m.evaluate(2000);
  CHECK(v.clear);
  CHECK_FALSE(v.motion_allowed);
  CHECK(contains(v.why, "clear now, waiting for re-arm"));
  REQUIRE(m.rearm(2000));
  v = m.evaluate(3000);
  CHECK(v.motion_allowed);
  CHECK(v.why.empty());
}

TEST_CASE("an e-stop trips the latch once; clearing it does not re-arm") {
  SafetyMonitor m(kNode);
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  m.on_heartbeat(can::NmtState::operational, 8'000);
  can::SafetyState pressed;
  pressed.estop_pressed = true;
  m.on_state(pressed, 10'000);
  SafetyVerdict v = m.evaluate(10'000);
  CHECK(v.stop_now);
  CHECK_FALSE(v.motion_allowed);
  CHECK(contains(v.why, "e-stop pressed on safety node 17"));
  CHECK(m.trips() == 1);
  CHECK(m.last_trip().at_us == 10'000);
  CHECK(m.last_trip().state_stamp_us == 10'000);
  CHECK(m.last_trip().heartbeat_stamp_us == 8'000);
  CHECK(contains(m.last_trip().why, "e-stop pressed"));
  v = m.evaluate(20'000);
  CHECK_FALSE(v.stop_now);  // only once per trip
  CHECK_FALSE(v.motion_allowed);

  m.on_state(can::SafetyState{}, 30'000);  // released
  m.on_heartbeat(can::NmtState::operational, 30'000);
  v = m.evaluate(30'000);
  CHECK_FALSE(v.motion_allowed);  // latched
  CHECK(v.clear);
  CHECK(contains(v.why, "e-stop pressed"));
  REQUIRE(m.rearm(30'000));
  CHECK(m.evaluate(30'000).motion_allowed);
}

TEST_CASE("a bumper hit trips and names the segments") {
  SafetyMonitor m(kNode);
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  can::SafetyState s;
  s.bumpers = 0x12;
  m.on_state(s, 1000);
  const SafetyVerdict v = m.evaluate(1000);
  CHECK(v.stop_now);
  CHECK(contains(v.why, "bumper hit"));
  CHECK(contains(v.why, "front 0x0002"));
  CHECK(contains(v.why, "rear 0x0001"));
}

TEST_CASE("a missing heartbeat trips after three periods, not before") {
  SafetyMonitor m(kNode);  // 100 ms heartbeat, 50 ms state
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  // States keep coming (a node whose heartbeat task died), heartbeats do not.
  for (std::int64_t t = 50'000; t <= 300'000; t += 50'000) {
    m.on_state(can::SafetyState{}, t);
    CHECK(m.evaluate(t).motion_allowed);
  }
  m.on_state(can::SafetyState{}, 301'000);
  const SafetyVerdict v = m.evaluate(301'000);
  CHECK(v.stop_now);
  CHECK(contains(v.why, "heartbeat missing for 301 ms (limit 3 periods of 100 ms)"));
}

TEST_CASE("a stale state trips, and so does a node that is not operational") {
  SafetyMonitor m(kNode);
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  m.on_heartbeat(can::NmtState::operational, 100'000);
  CHECK(m.evaluate(150'000).motion_allowed);
  SafetyVerdict v = m.evaluate(150'001);
  CHECK(v.stop_now);
  CHECK(contains(v.why, "state stale"));

  SafetyMonitor n(kNode);
  healthy(n, 0);
  REQUIRE(n.rearm(0));
  n.on_heartbeat(can::NmtState::pre_operational, 10'000);
  v = n.evaluate(10'000);
  CHECK(v.stop_now);
  CHECK(contains(v.why, "pre-operational, not operational"));
}

TEST_CASE("a bus-off trips; recovery needs the node clear again and a re-arm") {
  SafetyMonitor m(kNode);
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  m.on_bus_state(hal::CanBusState::bus_off, "error frame: bus-off");
  SafetyVerdict v = m.evaluate(1000);
  CHECK(v.stop_now);
  CHECK(contains(v.why, "CAN bus bus-off (error frame: bus-off)"));
  m.on_bus_state(hal::CanBusState::error_active, "");
  CHECK(m.evaluate(2000).clear);  // node data still fresh
  CHECK_FALSE(m.evaluate(2000).motion_allowed);
  REQUIRE(m.rearm(2000));
}

TEST_CASE("EMCY faults block until an error reset; a reboot forgets old faults") {
  SafetyMonitor m(kNode);
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  can::Emergency e;
  e.error_code = can::emcy_code::kEstopCircuit;
  m.on_emergency(e);
  SafetyVerdict v = m.evaluate(1000);
  CHECK(v.stop_now);
  CHECK(contains(v.why, "EMCY 0xFF01 (e-stop circuit fault)"));
  healthy(m, 2000);
  auto refused = m.rearm(2000);
  REQUIRE_FALSE(refused);
  CHECK(contains(refused.error().message, "EMCY 0xFF01"));
  m.on_emergency(can::Emergency{});  // error reset
  REQUIRE(m.rearm(2000));

  m.on_emergency(e);
  m.evaluate(3000);
  m.on_heartbeat(can::NmtState::boot_up, 4000);
  CHECK(contains(*m.blocking_reason(4000), "boot-up"));
  healthy(m, 5000);
  CHECK_FALSE(m.blocking_reason(5000));
}

TEST_CASE("the node's own fault flag trips") {
  SafetyMonitor m(kNode);
  healthy(m, 0);
  REQUIRE(m.rearm(0));
  can::SafetyState s;
  s.fault = true;
  m.on_state(s, 1000);
  CHECK(contains(m.evaluate(1000).why, "reports a fault"));
}
