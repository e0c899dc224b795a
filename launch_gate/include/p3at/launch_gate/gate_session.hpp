#pragma once
/// The launch gate on the team link: publishes this robot's verdict, listens
/// for the teammates' and decides with TeamAgreement (docs/launch-gate.md).
/// Nothing moves during a session: the caller only keeps its robot's
/// connection alive through `pace`.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/launch_gate/team_agreement.hpp"

namespace p3at::gate {

struct SessionOptions {
  std::int64_t timeout_us = 30'000'000;     ///< how long to wait for every teammate's verdict
  std::int64_t republish_us = 200'000;      ///< own verdict is republished this often (best effort)
  std::int64_t step_us = 50'000;            ///< longest wait between two looks at the link
  /// After a refusal, keep publishing own verdict so teammates hear why (a
  /// NO-GO, or the hash they disagree with) before this robot exits: at least
  /// this long, and on until every teammate has been heard from or timeout_us
  /// (from the start) has passed.
  std::int64_t refusal_linger_us = 1'000'000;
  /// A robot that has committed (docs/launch-gate.md) waits this long past
  /// timeout_us for its teammates' commitments before it gives up in doubt.
  std::int64_t doubt_us = 5'000'000;
};

struct SessionResult {
  Agreement agreement;
  bool interrupted = false;                         ///< `stop` was set before a decision
  std::vector<hal::TeamNotification> early;         ///< notifications received meanwhile: hand them to the executive
  hal::GateVerdict published;                       ///< the last verdict published (on launch: GO with the session; keep publishing it)
  std::uint64_t verdicts_published = 0;
  std::int64_t waited_us = 0;                       ///< from start to decision
};

/// Runs the gate with `own` (own.robot and own.nonce set: fresh_gate_nonce())
/// for the team `roster`, reading
/// `clock` for every time (publishing, polling, the timeout). `pace(deadline_us)`
/// waits until about `deadline_us` (mission_exec: the robot's SIPs, so its
/// connection stays alive; default: clock.sleep_until_us). Returns once
/// decided, or with interrupted = true when `stop` becomes true.
SessionResult run_gate_session(hal::TeamLink& link, hal::Clock& clock, const hal::GateVerdict& own,
                               const std::vector<std::string>& roster, const SessionOptions& options,
                               const std::function<void(std::int64_t deadline_us)>& pace = {},
                               const std::atomic<bool>* stop = nullptr);

}  // namespace p3at::gate
