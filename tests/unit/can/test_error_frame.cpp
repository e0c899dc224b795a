#include <doctest/doctest.h>

#include <array>

#include "socketcan/error_frame.hpp"

// Error classes and data bytes are the kernel ABI (linux/can/error.h), written
// as numbers here so the test does not include OS headers.
using p3at::hal::CanBusState;
using p3at::hal::socketcan::decode_error_frame;

namespace {
constexpr std::uint32_t kErrFlag = 0x20000000;
}

TEST_CASE("bus-off and restart error frames change the state") {
  std::array<std::uint8_t, 8> data{};
  auto off = decode_error_frame(kErrFlag | 0x40, data);
  REQUIRE(off.state);
  CHECK(*off.state == CanBusState::bus_off);
  CHECK(off.description == "bus-off");
  auto restarted = decode_error_frame(kErrFlag | 0x100, data);
  REQUIRE(restarted.state);
  CHECK(*restarted.state == CanBusState::error_active);
}

TEST_CASE("controller error frames report warning, passive, active and overflows") {
  std::array<std::uint8_t, 8> data{};
  data[1] = 0x08;  // TX warning
  auto warning = decode_error_frame(kErrFlag | 0x04, data);
  REQUIRE(warning.state);
  CHECK(*warning.state == CanBusState::error_warning);
  data[1] = 0x10 | 0x04;  // RX passive and RX warning: the worse wins
  auto passive = decode_error_frame(kErrFlag | 0x04, data);
  REQUIRE(passive.state);
  CHECK(*passive.state == CanBusState::error_passive);
  data[1] = 0x40;
  auto active = decode_error_frame(kErrFlag | 0x04, data);
  REQUIRE(active.state);
  CHECK(*active.state == CanBusState::error_active);
  data[1] = 0x01;
  auto overflow = decode_error_frame(kErrFlag | 0x04, data);
  CHECK(overflow.overflow);
  CHECK_FALSE(overflow.state);
}

TEST_CASE("other error classes are described without a state change, counters are read") {
  std::array<std::uint8_t, 8> data{};
  data[6] = 130;
  data[7] = 7;
  auto ack = decode_error_frame(kErrFlag | 0x20 | 0x200, data);
  CHECK_FALSE(ack.state);
  CHECK(ack.description == "no ack");
  REQUIRE(ack.has_counters);
  CHECK(ack.tx_error_counter == 130);
  CHECK(ack.rx_error_counter == 7);
  CHECK(decode_error_frame(kErrFlag, data).description == "unspecified error");
}
