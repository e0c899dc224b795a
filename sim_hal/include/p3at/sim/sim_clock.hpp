#pragma once
/// Synthetic time for fast-time runs: never sleeps, only moves when told.

#include <cstdint>

#include "p3at/hal/clock.hpp"

namespace p3at::sim {

/// A hal::Clock whose sleep_until_us() jumps to the deadline instead of waiting.
/// Starts at `start_us`. Not thread-safe: one thread drives a fast-time run.
class SimClock final : public hal::Clock {
 public:
  explicit SimClock(std::int64_t start_us = 0) : now_us_(start_us) {}

  std::int64_t now_us() const override { return now_us_; }

  /// Advances to the deadline at once (never backwards).
  void sleep_until_us(std::int64_t deadline_us) override { advance_to_us(deadline_us); }

  /// Advances by `delta_us` (negative values are ignored: time is monotonic).
  void advance_us(std::int64_t delta_us) {
    if (delta_us > 0) now_us_ += delta_us;
  }

  /// Advances to `time_us` if it is later than now.
  void advance_to_us(std::int64_t time_us) {
    if (time_us > now_us_) now_us_ = time_us;
  }

 private:
  std::int64_t now_us_;
};

}  // namespace p3at::sim
