#include <doctest/doctest.h>

#include <chrono>
#include <cstdint>
#include <limits>

#include "p3at/hal/clock.hpp"

using p3at::hal::SteadyClock;

TEST_CASE("SteadyClock is monotonic and counts microseconds") {
  SteadyClock clock;
  std::int64_t previous = clock.now_us();
  for (int i = 0; i < 10000; ++i) {
    const std::int64_t now = clock.now_us();
    CHECK(now >= previous);
    previous = now;
  }
  // Agrees with std::chrono::steady_clock, in microseconds.
  const auto reference_us = std::chrono::duration_cast<std::chrono::microseconds>(
                                std::chrono::steady_clock::now().time_since_epoch())
                                .count();
  CHECK(clock.now_us() - reference_us >= 0);
  CHECK(clock.now_us() - reference_us < 100'000);
}

TEST_CASE("sleep_until_us reaches the deadline without oversleeping much") {
  SteadyClock clock;
  for (const std::int64_t step_us : {1'000, 20'000, 50'000}) {
    const std::int64_t deadline = clock.now_us() + step_us;
    clock.sleep_until_us(deadline);
    const std::int64_t woke = clock.now_us();
    CHECK(woke >= deadline);
    CHECK(woke - deadline < 50'000);  // generous for loaded CI machines
  }
}

TEST_CASE("sleep_until_us with a past deadline returns at once") {
  SteadyClock clock;
  const std::int64_t start = clock.now_us();
  clock.sleep_until_us(start - 1'000'000);
  clock.sleep_until_us(std::numeric_limits<std::int64_t>::min());
  CHECK(clock.now_us() - start < 20'000);
}

TEST_CASE("a fixed-rate loop paced by sleep_until_us keeps its period") {
  SteadyClock clock;
  constexpr std::int64_t kPeriodUs = 10'000;
  const std::int64_t start = clock.now_us();
  std::int64_t next = start;
  for (int i = 0; i < 10; ++i) {
    next += kPeriodUs;
    clock.sleep_until_us(next);
    CHECK(clock.now_us() >= next);
  }
  const std::int64_t elapsed = clock.now_us() - start;
  CHECK(elapsed >= 10 * kPeriodUs);
  CHECK(elapsed < 10 * kPeriodUs + 50'000);
}
