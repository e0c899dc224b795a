#pragma once
/// One robot's part of a mission behind the launch gate, from the pre-launch
/// check to the final status: what mission_exec does once its flags are read
/// (docs/launch-gate.md, docs/executive.md).
///  1. the pre-launch check (the same as `vipars gate`), before anything else;
///  2. the team link (LCM, authenticated with the team key) and the robot's
///     firmware over ARCOS (serial or TCP), with the CAN accessories if asked;
///  3. the gate session: publish this robot's verdict with the mission's hash
///     and wait for every teammate's GO for the same hash (the robot's SIPs
///     keep its connection alive meanwhile);
///  4. the FSA at 10 Hz, re-verifying at each transition; then the drain of
///     the last re-verification, the repeated final status and the summary.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "p3at/launch_gate/pre_launch_check.hpp"

namespace p3at::gate {

struct MissionRunOptions {
  std::string robot;
  CheckRequest check;  ///< the mission, models and criteria: the pre-launch check's request
  std::optional<std::string> hal_url;
  std::optional<std::string> lcm_url;
  std::optional<std::string> team_key_file;
  const char* team_key_env = nullptr;  ///< $P3AT_TEAM_KEY, used when team_key_file is not given
  std::optional<std::string> can_url;
  double gate_timeout_s = 30.0;
  bool override_gate = false;
  std::uint64_t seed = 0;
  double linger_s = 5.0;
  std::uint32_t telemetry_every = 1;
  /// A teammate silent this long (wall time) during the mission is reported
  /// and the mission's abort_action taken (docs/executive.md, "Liveness").
  double teammate_silence_s = 3.0;
  /// Past Tmax + this (mission time) the mission aborts, saying so; 0 = never.
  double overtime_s = 30.0;
  /// A stall longer than this aborts (the firmware watchdog); 0 = never.
  std::int64_t stall_abort_ms = 2000;
  bool resume_after_stall = false;
};

/// Runs it; returns mission_exec's exit status (exit_codes.hpp). `stop`
/// (set by a signal) interrupts the gate or the mission; `arm_signals` is
/// called once setup is done, just before the robot is connected, so that a
/// signal during setup still ends the process at once.
int run_mission(const MissionRunOptions& options, std::atomic<bool>& stop, const std::function<void()>& arm_signals);

}  // namespace p3at::gate
