#pragma once
/// Time for every component comes from a Clock, never from the system directly,
/// so the same code runs in real time and in fast (simulated) time.

#include <cstdint>

namespace p3at::hal {

/// A monotonic clock in microseconds. Implementations: SteadyClock (real time)
/// and sim::SimClock (synthetic, advanced by the simulator, never sleeps).
class Clock {
 public:
  Clock() = default;
  Clock(const Clock&) = delete;
  Clock& operator=(const Clock&) = delete;
  virtual ~Clock() = default;

  /// Monotonic time in microseconds since an arbitrary epoch.
  virtual std::int64_t now_us() const = 0;

  /// Blocks (real time) or advances (simulated time) until now_us() >= deadline_us.
  virtual void sleep_until_us(std::int64_t deadline_us) = 0;
};

/// Real time from std::chrono::steady_clock.
class SteadyClock final : public Clock {
 public:
  std::int64_t now_us() const override;
  void sleep_until_us(std::int64_t deadline_us) override;
};

}  // namespace p3at::hal
