#pragma once
// Receiving with a deadline from a hal::CanBus, for the SocketCAN tests.

#include <doctest/doctest.h>

#include <cstdint>
#include <optional>

#include "can_test_env.hpp"
#include "p3at/hal/can_bus.hpp"

namespace p3at::test {

/// The next data frame within `timeout_ms`, or nullopt.
inline std::optional<hal::CanRxFrame> receive_within(hal::CanBus& bus, int timeout_ms) {
  const std::int64_t deadline = steady_us() + std::int64_t{timeout_ms} * 1000;
  for (;;) {
    auto rx = bus.receive();
    REQUIRE(rx);
    if (rx->has_value()) return **rx;
    const std::int64_t left_ms = (deadline - steady_us()) / 1000;
    if (left_ms <= 0) return std::nullopt;
    auto waited = bus.wait(static_cast<int>(left_ms));
    REQUIRE(waited);
  }
}

/// Reads (and drops) everything waiting for up to `ms` of quiet.
inline void drain(hal::CanBus& bus, int ms = 20) {
  while (receive_within(bus, ms)) {
  }
}

/// Calls receive() (which also processes error frames and link changes) until
/// `done()` holds or `timeout_ms` passes.
template <class Done>
bool pump_until(hal::CanBus& bus, int timeout_ms, Done done) {
  const std::int64_t deadline = steady_us() + std::int64_t{timeout_ms} * 1000;
  while (!done()) {
    if (steady_us() > deadline) return false;
    auto rx = bus.receive();
    REQUIRE(rx);
    if (!rx->has_value()) REQUIRE(bus.wait(5));
  }
  return true;
}

}  // namespace p3at::test
