#pragma once
/// The team's launch decision from the verdicts heard so far: pure, no I/O,
/// no clock (time comes in as an argument). docs/launch-gate.md, "The launch
/// as an agreement".
///
/// A teammate's verdict counts only once it is *current*: it echoes this
/// robot's nonce (its sender has heard this very gate). Replays of another
/// run never are. Rules, on every update(), in this order; a decision sticks:
///  1. this robot's own verdict is NO-GO                              → no_go
///  2. a current teammate's verdict carries a different mission hash  → mismatch
///  3. a current teammate's verdict is NO-GO                          → no_go
///  4. every teammate current, GO or OVERRIDE: this robot *commits*: it
///     computes the session id from the hash and every robot's nonce and
///     publishes it in its GO (not a decision yet)
///  5. committed, and every teammate's current verdict carries that session
///     (each has committed to the same robots' nonces)                → launch
///  6. not committed and timeout_us has passed                        → silent
///  7. committed and timeout_us + doubt_us has passed                 → in_doubt
/// Once committed, a robot never refuses by timeout (a teammate may already
/// have launched on its GO); only a NO-GO or a different hash from the very
/// teammate processes it committed with (which never published a commitment,
/// so nobody can have launched) still refuses. The published verdict after a
/// refusal is NO-GO with the reason; never the earlier GO.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "p3at/hal/team_link.hpp"

namespace p3at::gate {

enum class AgreementState {
  waiting,   ///< not every teammate has committed yet
  launch,    ///< every robot committed to this very session: start
  no_go,     ///< this robot or a teammate said NO-GO
  mismatch,  ///< a teammate verified a different mission or different models
  silent,    ///< a teammate was not heard (in this gate) within the timeout
  in_doubt,  ///< committed, but the teammates' commitments were not heard: do not move, say so
};
/// "waiting", "launch", "no-go", "mismatch", "silent", "in-doubt".
const char* to_string(AgreementState state);

struct Agreement {
  AgreementState state = AgreementState::waiting;
  std::string reason;                       ///< one line, for logs and refusals
  std::vector<std::string> silent;          ///< teammates without a current verdict
  std::vector<std::string> deaf;            ///< of those, teammates heard but not hearing this robot
  std::vector<hal::GateVerdict> team;       ///< own first, then the current teammates' verdicts by roster
  bool committed = false;
  std::string session;                      ///< the session id once committed
};

class TeamAgreement {
 public:
  /// `own.robot` and `own.nonce` must be set; `roster` lists every robot of
  /// the team (own included).
  TeamAgreement(hal::GateVerdict own, std::vector<std::string> roster, std::int64_t start_us, std::int64_t timeout_us,
                std::int64_t doubt_us = 5'000'000);

  /// Decides from `teammates` (the link's latest verdict of each) at `now_us`.
  const Agreement& update(std::int64_t now_us, const std::vector<hal::GateVerdict>& teammates);
  /// Only refreshes the nonces echoed in published() (also after a decision).
  void observe(const std::vector<hal::GateVerdict>& teammates);

  const Agreement& current() const { return agreement_; }
  bool decided() const { return agreement_.state != AgreementState::waiting; }
  const hal::GateVerdict& own() const { return own_; }
  /// What this robot should publish now: its verdict with the teammates'
  /// nonces it has heard and, once committed, the session; after a refusal,
  /// NO-GO with the reason.
  const hal::GateVerdict& published() const { return published_; }
  /// True when `v` echoes this robot's nonce.
  bool is_current(const hal::GateVerdict& v) const;

 private:
  void decide(AgreementState state, std::string reason);

  hal::GateVerdict own_;
  hal::GateVerdict published_;
  std::vector<std::string> teammates_;  ///< roster without own, in roster order
  std::int64_t start_us_;
  std::int64_t timeout_us_;
  std::int64_t doubt_us_;
  std::map<std::string, std::string> committed_nonces_;  ///< teammate → nonce, fixed at commit
  Agreement agreement_;
};

}  // namespace p3at::gate
