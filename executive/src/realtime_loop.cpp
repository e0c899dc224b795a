#include "p3at/executive/realtime_loop.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

#include "p3at/common/log.hpp"

namespace p3at::exec {
namespace {

constexpr const char* kLog = "executive";

std::int64_t wall_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// One paced iteration: wait for an update (bounded), take any others already
/// queued (after a stall), then cycle.
class Pacer {
 public:
  Pacer(RobotExecutive& executive, hal::DriveBase& drive, const RealtimeOptions& options)
      : executive_(executive), drive_(drive), options_(options) {}

  void step() {
    hal::Clock& clock = executive_.clock();
    const Result<bool> waited = drive_.wait_for_update(options_.update_timeout_ms);
    const bool updated = waited.ok() && waited.value();
    if (!waited.ok() && errors_++ % 50 == 0) {
      log::warn(kLog, "event=wait-error robot=" + executive_.robot().name + " error=\"" + waited.error().message + "\"");
    }
    if (updated && last_wall_us_ && wall_us() - *last_wall_us_ > 2 * executive_.options().period_us) {
      // This process did not run for a while (stopped, starved): updates
      // queued up meanwhile. Take them all now (wait_for_update(0) returns
      // only what has already arrived), so the cycle acts on the newest
      // (bounded: a flood cannot hold us).
      for (int i = 0; i < 1000; ++i) {
        const Result<bool> more = drive_.wait_for_update(0);
        if (!more.ok() || !more.value()) break;
      }
    }
    if (!updated && last_cycle_us_) {
      // Returned early without an update: do not run cycles faster than the period.
      const std::int64_t earliest_us = *last_cycle_us_ + executive_.options().period_us;
      if (clock.now_us() < earliest_us) clock.sleep_until_us(earliest_us);
    }
    check_stall();
    last_cycle_us_ = clock.now_us();
    executive_.cycle();
  }

 private:
  /// Compares this cycle with the last: wall time between them, and how many
  /// controller updates arrived (one per period when all is well).
  void check_stall() {
    const std::int64_t now_wall_us = wall_us();
    const std::uint64_t count = drive_.state().update_count;
    if (last_wall_us_ && last_count_) {
      const std::int64_t period_us = executive_.options().period_us;
      const std::int64_t gap_us = now_wall_us - *last_wall_us_;
      const std::uint64_t updates = count >= *last_count_ ? count - *last_count_ : 0;
      if (gap_us > 2 * period_us || updates >= 3) {
        // Missed cycles: by the controller's updates (right under a fast
        // simulator too), or by wall time when the controller fell silent as well.
        const std::uint64_t by_updates = updates > 0 ? updates - 1 : 0;
        const std::int64_t periods = gap_us / period_us;
        const std::uint64_t by_wall = periods > 1 ? static_cast<std::uint64_t>(periods - 1) : 0;
        const std::uint64_t missed = std::max(by_updates, by_wall);
        // Controller time the stall lasted (what the firmware's watchdog saw).
        const std::int64_t stall_ms =
            std::max(gap_us, static_cast<std::int64_t>(updates) * period_us) / 1000;
        executive_.note_stall(missed, stall_ms);
        log::warn(kLog, "event=stall robot=" + executive_.robot().name + " gap_ms=" + std::to_string(gap_us / 1000) +
                            " stall_ms=" + std::to_string(stall_ms) + " missed_cycles=" + std::to_string(missed) +
                            " updates_skipped=" + std::to_string(by_updates) + " (resynchronised on the newest update)");
        if (options_.stall_abort_ms > 0 && stall_ms > options_.stall_abort_ms && executive_.running()) {
          if (options_.resume_after_stall) {
            log::warn(kLog, "event=stall-resume robot=" + executive_.robot().name + " stall_ms=" +
                                std::to_string(stall_ms) + " watchdog_ms=" + std::to_string(options_.stall_abort_ms) +
                                " (longer than the firmware watchdog: the robot was halted; resuming as asked)");
          } else {
            executive_.abort("stalled for " + std::to_string(stall_ms) + " ms, longer than the firmware watchdog (" +
                             std::to_string(options_.stall_abort_ms) + " ms): the robot was halted meanwhile");
          }
        }
      }
    }
    last_wall_us_ = now_wall_us;
    last_count_ = count;
  }

  RobotExecutive& executive_;
  hal::DriveBase& drive_;
  const RealtimeOptions& options_;
  std::optional<std::int64_t> last_cycle_us_;
  std::optional<std::int64_t> last_wall_us_;
  std::optional<std::uint64_t> last_count_;
  std::uint64_t errors_ = 0;
};

}  // namespace

Outcome run_realtime(RobotExecutive& executive, hal::DriveBase& drive, const std::atomic<bool>& stop_requested,
                     const RealtimeOptions& options) {
  Pacer pacer(executive, drive, options);
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
