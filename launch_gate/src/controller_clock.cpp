#include "p3at/launch_gate/controller_clock.hpp"

#include <algorithm>

namespace p3at::gate {

std::int64_t ControllerClock::now_us() const {
  const std::uint64_t count = drive_.state().update_count;
  const std::int64_t wall_us = wall_.now_us();
  if (!origin_count_) {
    origin_count_ = count;
    last_count_ = count;
    last_change_wall_us_ = wall_us;
  }
  if (count != last_count_) {
    last_count_ = count;
    last_change_wall_us_ = wall_us;
  }
  // A controller that restarts its count (a reconnect) must not turn time back.
  const std::uint64_t sips = count >= *origin_count_ ? count - *origin_count_ : 0;
  const std::int64_t controller_us = static_cast<std::int64_t>(sips) * period_us_;
  const std::int64_t stalled_us = std::max<std::int64_t>(0, wall_us - last_change_wall_us_ - stall_us_);
  last_returned_us_ = std::max(last_returned_us_, controller_us + stalled_us);
  return last_returned_us_;
}

void ControllerClock::sleep_until_us(std::int64_t deadline_us) {
  const std::int64_t now = now_us();
  if (deadline_us <= now) return;
  wall_.sleep_until_us(wall_.now_us() + (deadline_us - now));
}

}  // namespace p3at::gate
