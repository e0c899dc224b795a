#pragma once
/// The real-time driver of a RobotExecutive: one cycle per controller update
/// (SIP arrival, every 100 ms on a Pioneer). Fast time needs no driver from
/// here: a simulator calls RobotExecutive::cycle() itself (see robot_executive.hpp).

#include <atomic>
#include <cstdint>
#include <string>

#include "p3at/executive/robot_executive.hpp"
#include "p3at/hal/drive_base.hpp"

namespace p3at::exec {

struct RealtimeOptions {
  /// How long to wait for a controller update before running the cycle anyway
  /// (it then counts as a missed update): 1.5 periods.
  int update_timeout_ms = 150;
  /// After the mission finishes or aborts, keep cycling (the robot stopped) for at
  /// most this long, so teammates still get this robot's acknowledgements and
  /// status, until every teammate has finished or aborted. 0 = return at once.
  std::int64_t linger_ms = 0;
  /// The abort reason when `stop_requested` ends the mission.
  std::string interrupt_reason = "interrupted";
  /// A stall (docs/executive.md, "Stalls"): more than two periods of wall
  /// time between two cycles, or three or more controller updates at once.
  /// One that lasted longer than this (the firmware's watchdog: 2 s) aborts
  /// the mission: the firmware has halted the robot meanwhile and the world
  /// moved on. 0 = never abort for a stall.
  std::int64_t stall_abort_ms = 2000;
  /// Instead of aborting after such a stall, go on (saying so).
  bool resume_after_stall = false;
};

/// Runs `executive` until it finishes or aborts, or `stop_requested` becomes true
/// (then it aborts with options.interrupt_reason). Each iteration: wait_for_update()
/// for at most update_timeout_ms, then cycle(). If the drive base returns early
/// without an update, the loop waits out the rest of the period on the
/// executive's clock, so a failing base cannot spin the CPU. On the way out the
/// robot is stopped (DriveBase::stop()). Returns the final outcome. `drive` must
/// be the DriveBase the executive was built with.
///
/// After a stall (more than two periods of wall time since the last cycle),
/// the loop first takes every controller update already queued
/// (DriveBase::wait_for_update(0)), so the next cycle runs on the newest one instead of replaying
/// stale ones (each would send a motion command computed from the past); the
/// stall is logged (`event=stall`) and counted (CycleStats::stalls,
/// missed_cycles), and a long one aborts (see stall_abort_ms).
Outcome run_realtime(RobotExecutive& executive, hal::DriveBase& drive, const std::atomic<bool>& stop_requested,
                     const RealtimeOptions& options = {});

}  // namespace p3at::exec
