#pragma once
/// The mission clock: the robot controller's own time, one 100 ms period per
/// SIP (DriveState::update_count), so that mission times in logs and in
/// in-mission re-verification are in the same time the verifier predicts and
/// the robot moves in, also when a simulator runs faster than real time
/// (`p3at_sim --speedup X`). docs/launch-gate.md.
///
/// now_us() = (update_count − update_count at the first call) × period_us,
/// plus, only while no SIP has arrived for longer than `stall_us` of wall
/// time, the wall time beyond that (so loops bounded by this clock still end
/// when the controller falls silent); never decreasing. sleep_until_us()
/// sleeps the difference in wall time (it is only used when SIPs are late).

#include <cstdint>
#include <optional>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/drive_base.hpp"

namespace p3at::gate {

class ControllerClock final : public hal::Clock {
 public:
  /// `drive` and `wall` must outlive this clock.
  ControllerClock(const hal::DriveBase& drive, hal::Clock& wall, std::int64_t period_us = 100'000,
                  std::int64_t stall_us = 150'000)
      : drive_(drive), wall_(wall), period_us_(period_us), stall_us_(stall_us) {}

  std::int64_t now_us() const override;
  void sleep_until_us(std::int64_t deadline_us) override;

 private:
  const hal::DriveBase& drive_;
  hal::Clock& wall_;
  std::int64_t period_us_;
  std::int64_t stall_us_;
  // now_us() is const in hal::Clock; these only record what it has seen.
  mutable std::optional<std::uint64_t> origin_count_;
  mutable std::uint64_t last_count_ = 0;
  mutable std::int64_t last_change_wall_us_ = 0;
  mutable std::int64_t last_returned_us_ = 0;
};

}  // namespace p3at::gate
