#pragma once
// A manual clock for unit tests: time moves only when the test (or a
// sleep_until_us call) moves it.

#include <cstdint>

#include "p3at/hal/clock.hpp"

namespace p3at::test {

class FakeClock final : public hal::Clock {
 public:
  explicit FakeClock(std::int64_t start_us = 1'000'000) : now_us_(start_us) {}
  std::int64_t now_us() const override { return now_us_; }
  void sleep_until_us(std::int64_t deadline_us) override {
    if (deadline_us > now_us_) now_us_ = deadline_us;
  }
  void advance_us(std::int64_t delta_us) { now_us_ += delta_us; }

 private:
  std::int64_t now_us_;
};

}  // namespace p3at::test
