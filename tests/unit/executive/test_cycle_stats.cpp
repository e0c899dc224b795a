// Cycle statistics: percentiles from a fixed window, overruns, missed updates.

#include <doctest/doctest.h>

#include "p3at/executive/cycle_stats.hpp"

using p3at::exec::CycleStats;

TEST_CASE("cycle stats: empty") {
  const CycleStats s(100'000);
  CHECK(s.cycles() == 0);
  CHECK(s.p50_us() == 0.0);
  CHECK(s.p99_us() == 0.0);
}

TEST_CASE("cycle stats: nearest-rank percentiles of 1..100") {
  CycleStats s(100'000);
  // Recorded out of order: the percentile does not depend on arrival order.
  for (int i = 100; i >= 1; --i) s.record(static_cast<double>(i), false);
  CHECK(s.cycles() == 100);
  CHECK(s.p50_us() == 50.0);
  CHECK(s.p99_us() == 99.0);
  CHECK(s.percentile_us(1.0) == 100.0);
  CHECK(s.percentile_us(0.0) == 1.0);
  CHECK(s.max_us() == 100.0);
}

TEST_CASE("cycle stats: overruns and missed updates are counted") {
  CycleStats s(1000);
  s.record(999.0, false);
  s.record(1000.0, true);   // equal to the period: not an overrun
  s.record(1000.5, false);  // overrun
  s.record(50'000.0, true); // overrun
  CHECK(s.overruns() == 2);
  CHECK(s.missed_updates() == 2);
  CHECK(s.cycles() == 4);
}

TEST_CASE("cycle stats: the window keeps only the latest samples") {
  CycleStats s(100'000);
  for (std::size_t i = 0; i < CycleStats::kWindow; ++i) s.record(1000.0, false);
  for (std::size_t i = 0; i < CycleStats::kWindow; ++i) s.record(10.0, false);
  CHECK(s.p99_us() == 10.0);  // the old 1000 µs samples have left the window
  CHECK(s.max_us() == 1000.0);  // the all-time maximum stays
  CHECK(s.cycles() == 2 * CycleStats::kWindow);
}
