// The SocketCAN backend on a real kernel: round trips, kernel timestamps,
// receive filters, non-blocking calls, error frames (bus-off, restart), and
// the interface going down, coming back, and being removed and re-created.
#include <doctest/doctest.h>

#include <array>
#include <chrono>
#include <string>
#include <thread>

#include "bus_helpers.hpp"
#include "can_test_env.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/protocols/can/frame.hpp"

namespace can = p3at::can;
namespace hal = p3at::hal;
using p3at::test::can_interface;
using p3at::test::can_url;
using p3at::test::receive_within;
using p3at::test::shell;

namespace {

std::unique_ptr<hal::CanBus> open_bus(const std::string& url) {
  auto bus = hal::open_can_bus(url);
  REQUIRE_MESSAGE(bus, (bus ? "" : bus.error().message));
  return std::move(*bus);
}

can::Frame frame_of(const char* text) {
  auto f = can::parse_frame(text);
  REQUIRE(f);
  return *f;
}

// A private vcan interface for tests that take it down or remove it.
struct PrivateInterface {
  std::string name = "p3atbus0";
  PrivateInterface() {
    shell("ip link del " + name + " 2>/dev/null");
    REQUIRE(shell("ip link add dev " + name + " type vcan") == 0);
    REQUIRE(shell("ip link set " + name + " up") == 0);
  }
  ~PrivateInterface() { shell("ip link del " + name + " 2>/dev/null"); }
  std::string url() const { return "socketcan://" + name; }
};

}  // namespace

TEST_CASE("opening reports missing interfaces and bad URLs as errors") {
  auto missing = hal::open_can_bus("socketcan://nosuchcan7");
  REQUIRE_FALSE(missing);
  CHECK(missing.error().code == p3at::Error::Code::not_found);
  CHECK(missing.error().message.find("nosuchcan7") != std::string::npos);
  CHECK_FALSE(hal::open_can_bus("socketcan://"));
  CHECK_FALSE(hal::open_can_bus("socketcan://averyveryverylongname0"));
  CHECK_FALSE(hal::open_can_bus("socketcan://vcan0:5"));
  CHECK_FALSE(hal::open_can_bus("socketcan://vcan0?loopback=maybe"));
  CHECK_FALSE(hal::open_can_bus("socketcan://vcan0?bitrate=500000"));
  auto scheme = hal::open_can_bus("slcan:///dev/ttyACM0");
  REQUIRE_FALSE(scheme);
  CHECK(scheme.error().message.find("unknown CAN bus scheme") != std::string::npos);
}

TEST_CASE("frames travel between two sockets, non-blocking, with kernel timestamps") {
  auto a = open_bus(can_url());
  auto b = open_bus(can_url());
  CHECK(a->describe() == can_url());
  p3at::test::drain(*b);
  auto nothing = b->receive();
  REQUIRE(nothing);
  CHECK_FALSE(nothing->has_value());  // returns at once
  CHECK_FALSE(*b->wait(0));

  const can::Frame sent = frame_of("190#40420F00B80B0700");
  REQUIRE(a->send(sent));
  REQUIRE(a->send(frame_of("1F334455#DEADBEEF")));
  REQUIRE(a->send(frame_of("123#R2")));
  CHECK(*b->wait(1000));
  // Read late: a kernel timestamp is the arrival time, not the time of the read.
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  auto first = receive_within(*b, 1000);
  REQUIRE(first);
  const std::int64_t read_us = p3at::test::steady_us();
  CHECK(first->frame == sent);
  CHECK(read_us - first->stamp_us >= 50'000);
  CHECK(read_us - first->stamp_us < 2'000'000);
  auto ext = receive_within(*b, 1000);
  REQUIRE(ext);
  CHECK(ext->frame.extended);
  CHECK(ext->frame.id == 0x1F334455);
  CHECK(ext->stamp_us >= first->stamp_us);
  auto rtr = receive_within(*b, 1000);
  REQUIRE(rtr);
  CHECK(rtr->frame.remote);
  CHECK(rtr->frame.length == 2);
  CHECK(a->status().frames_sent == 3);
  CHECK(b->status().frames_received == 3);
  CHECK_FALSE(receive_within(*a, 50));  // no echo of our own frames by default
}

TEST_CASE("receive filters are applied by the kernel") {
  auto a = open_bus(can_url());
  auto b = open_bus(can_url());
  const std::array<hal::CanFilter, 2> filters{hal::CanFilter{0x190, 0x7FF, false},
                                              hal::CanFilter{0x700, 0x780, false}};
  REQUIRE(b->set_filters(filters));
  p3at::test::drain(*b);
  REQUIRE(a->send(frame_of("191#000000FF")));
  REQUIRE(a->send(frame_of("00000190#00")));  // extended 0x190: another format
  REQUIRE(a->send(frame_of("711#05")));
  REQUIRE(a->send(frame_of("190#01")));
  auto r1 = receive_within(*b, 1000);
  REQUIRE(r1);
  CHECK(can::format_frame(r1->frame) == "711#05");
  auto r2 = receive_within(*b, 1000);
  REQUIRE(r2);
  CHECK(can::format_frame(r2->frame) == "190#01");
  CHECK_FALSE(receive_within(*b, 100));
  REQUIRE(b->set_filters({}));  // back to everything
  REQUIRE(a->send(frame_of("191#000000FF")));
  CHECK(receive_within(*b, 1000));
}

TEST_CASE("loopback=0 hides our frames from other sockets; receive_own=1 shows them to us") {
  auto quiet = open_bus(can_url() + "?loopback=0");
  auto own = open_bus(can_url() + "?receive_own=1");
  auto other = open_bus(can_url());
  p3at::test::drain(*other);
  REQUIRE(quiet->send(frame_of("321#01")));
  CHECK_FALSE(receive_within(*other, 100));
  REQUIRE(own->send(frame_of("321#02")));
  auto echo = receive_within(*own, 1000);
  REQUIRE(echo);
  CHECK(can::format_frame(echo->frame) == "321#02");
}

TEST_CASE("controller error frames: bus-off is reported, sending refused, restart recovers") {
  PrivateInterface iface;
  auto bus = open_bus(iface.url());
  auto peer = open_bus(iface.url());
  // What a CAN controller's driver emits, injected with cansend (8-digit id with CAN_ERR_FLAG).
  REQUIRE(shell("cansend " + iface.name + " 20000004#0010000000000000") == 0);  // controller: rx-passive
  REQUIRE(p3at::test::pump_until(*bus, 2000, [&] { return bus->status().state == hal::CanBusState::error_passive; }));
  REQUIRE(shell("cansend " + iface.name + " 20000040#0000000000000000") == 0);  // bus-off
  REQUIRE(p3at::test::pump_until(*bus, 2000, [&] { return bus->status().state == hal::CanBusState::bus_off; }));
  CHECK(bus->status().bus_off_events == 1);
  CHECK(bus->status().error_frames == 2);
  CHECK(bus->status().last_error.find("bus-off") != std::string::npos);
  auto refused = bus->send(frame_of("123#00"));
  REQUIRE_FALSE(refused);
  CHECK(refused.error().code == p3at::Error::Code::state);
  CHECK(bus->status().send_failures == 1);

  REQUIRE(shell("cansend " + iface.name + " 20000100#0000000000000000") == 0);  // controller restarted
  REQUIRE(p3at::test::pump_until(*bus, 2000, [&] { return bus->status().state == hal::CanBusState::error_active; }));
  CHECK(bus->status().recoveries == 1);
  p3at::test::drain(*peer);
  REQUIRE(bus->send(frame_of("123#01")));
  CHECK(receive_within(*peer, 1000));
}

TEST_CASE("the interface going down is reported, and traffic resumes when it comes back") {
  PrivateInterface iface;
  auto bus = open_bus(iface.url());
  auto peer = open_bus(iface.url());
  REQUIRE(shell("ip link set " + iface.name + " down") == 0);
  CHECK_FALSE(bus->send(frame_of("123#00")));  // the kernel says ENETDOWN
  CHECK(bus->status().state == hal::CanBusState::down);
  CHECK(bus->status().down_events == 1);
  REQUIRE(shell("ip link set " + iface.name + " up") == 0);
  REQUIRE(p3at::test::pump_until(*bus, 2000, [&] { return bus->status().state == hal::CanBusState::error_active; }));
  CHECK(bus->status().recoveries == 1);
  p3at::test::drain(*peer);
  REQUIRE(bus->send(frame_of("123#02")));
  auto got = receive_within(*peer, 1000);
  REQUIRE(got);
  CHECK(can::format_frame(got->frame) == "123#02");
}

TEST_CASE("a removed interface is reported; the socket is reopened when it is re-created") {
  PrivateInterface iface;
  auto bus = open_bus(iface.url());
  REQUIRE(shell("ip link del " + iface.name) == 0);
  REQUIRE(p3at::test::pump_until(*bus, 2000, [&] { return bus->status().state == hal::CanBusState::down; }));
  CHECK_FALSE(bus->send(frame_of("123#00")));
  REQUIRE(shell("ip link add dev " + iface.name + " type vcan") == 0);
  REQUIRE(shell("ip link set " + iface.name + " up") == 0);
  REQUIRE(p3at::test::pump_until(*bus, 2000, [&] { return bus->status().state == hal::CanBusState::error_active; }));
  CHECK(bus->status().recoveries == 1);
  auto peer = open_bus(iface.url());
  REQUIRE(peer->send(frame_of("124#03")));
  auto got = receive_within(*bus, 1000);
  REQUIRE(got);
  CHECK(can::format_frame(got->frame) == "124#03");
}
