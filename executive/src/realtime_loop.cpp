#include "p3at/executive/realtime_loop.hpp"

#include <optional>
#include <string>

#include "p3at/common/log.hpp"

namespace p3at::exec {
namespace {

constexpr const char* kLog = "executive";

/// One paced iteration: wait for an update (bounded), then cycle.
class Pacer {
 public:
  Pacer(RobotExecutive& executive, hal::DriveBase& drive, int timeout_ms)
      : executive_(executive), drive_(drive), timeout_ms_(timeout_ms) {}

  void step() {
    hal::Clock& clock = executive_.clock();
    const Result<bool> waited = drive_.wait_for_update(timeout_ms_);
    const bool updated = waited.ok() && waited.value();
    if (!waited.ok() && errors_++ % 50 == 0) {
      log::warn(kLog, "event=wait-error robot=" + executive_.robot().name + " error=\"" + waited.error().message + "\"");
    }
    if (!updated && last_cycle_us_) {
      // Returned early without an update: do not run cycles faster than the period.
      const std::int64_t earliest_us = *last_cycle_us_ + executive_.options().period_us;
      if (clock.now_us() < earliest_us) clock.sleep_until_us(earliest_us);
    }
    last_cycle_us_ = clock.now_us();
    executive_.cycle();
  }

 private:
  RobotExecutive& executive_;
  hal::DriveBase& drive_;
  int timeout_ms_;
  std::optional<std::int64_t> last_cycle_us_;
  std::uint64_t errors_ = 0;
};

}  // namespace

Outcome run_realtime(RobotExecutive& executive, hal::DriveBase& drive, const std::atomic<bool>& stop_requested,
                     const RealtimeOptions& options) {
  Pacer pacer(executive, drive, options.update_timeout_ms);
  while (executive.running() && !stop_requested.load()) pacer.step();
  if (executive.running()) executive.abort(options.interrupt_reason);
  if (const Status st = drive.stop(); !st) {
    log::warn(kLog, "event=stop-failed robot=" + executive.robot().name + " error=\"" + st.error().message + "\"");
  }
  if (options.linger_ms > 0) {
    hal::Clock& clock = executive.clock();
    const std::int64_t deadline_us = clock.now_us() + options.linger_ms * 1000;
    while (!stop_requested.load() && !executive.team_settled() && clock.now_us() < deadline_us) pacer.step();
  }
  return executive.outcome();
}

}  // namespace p3at::exec
