#include <doctest/doctest.h>

#include <string>

#include "p3at/hal/can_bus.hpp"

// open_can_bus() on any host: URL problems and missing interfaces are error
// values naming what is wrong (the real socket paths run in tests/socketcan).
TEST_CASE("open_can_bus rejects malformed URLs, unknown schemes and options") {
  for (const char* url : {"socketcan://", "socketcan://can0:1", "socketcan://can0/x", "can0", "socketcan://a b",
                          "socketcan://averyveryverylongname0", "socketcan://can0?loopback=maybe",
                          "socketcan://can0?bitrate=500000"}) {
    CAPTURE(url);
    auto bus = p3at::hal::open_can_bus(url);
    REQUIRE_FALSE(bus);
    CHECK(bus.error().code == p3at::Error::Code::invalid_argument);
    CHECK_FALSE(bus.error().message.empty());
  }
  auto scheme = p3at::hal::open_can_bus("slcan:///dev/ttyACM0");
  REQUIRE_FALSE(scheme);
  CHECK(scheme.error().message.find("unknown CAN bus scheme 'slcan'") != std::string::npos);
}

TEST_CASE("open_can_bus reports a missing interface, naming it") {
  auto bus = p3at::hal::open_can_bus("socketcan://p3atnosuch0");
  REQUIRE_FALSE(bus);
  CHECK(bus.error().code == p3at::Error::Code::not_found);
  CHECK(bus.error().message.find("p3atnosuch0") != std::string::npos);
}

TEST_CASE("socketcan_available answers either way without crashing") {
  const p3at::Status st = p3at::hal::socketcan_available();
  if (!st) CHECK(st.error().message.find("socket(AF_CAN") != std::string::npos);
}
