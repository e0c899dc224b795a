#include "p3at/hal/clock.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

namespace p3at::hal {

std::int64_t SteadyClock::now_us() const {
  const auto since_epoch = std::chrono::steady_clock::now().time_since_epoch();
  return std::chrono::duration_cast<std::chrono::microseconds>(since_epoch).count();
}

void SteadyClock::sleep_until_us(std::int64_t deadline_us) {
  // Clamp so the conversion to the clock's nanoseconds cannot overflow (UB).
  constexpr std::int64_t kMaxUs =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::duration::max()).count();
  constexpr std::int64_t kMinUs =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::duration::min()).count();
  const std::int64_t clamped_us = std::clamp(deadline_us, kMinUs, kMaxUs);
  const std::chrono::steady_clock::time_point deadline{
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::microseconds(clamped_us))};
  // sleep_until may wake early on some platforms; loop until the contract holds.
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_until(deadline);
  }
}

}  // namespace p3at::hal
