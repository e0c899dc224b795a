#pragma once
/// The team's launch decision from the verdicts heard so far: pure, no I/O,
/// no clock (time comes in as an argument). docs/launch-gate.md.
///
/// Rules, checked on every update() in this order; the first decision sticks:
///  1. this robot's own verdict is NO-GO                      → no_go
///  2. a teammate's verdict carries a different mission hash  → mismatch
///  3. a teammate's verdict is NO-GO                          → no_go
///  4. every teammate's verdict is GO or OVERRIDE, same hash  → launch
///  5. timeout_us has passed since the start                  → silent (names who)
/// OVERRIDE counts as a vote to launch (the operator answered for it on that
/// robot); it never overrides a teammate's NO-GO, a hash mismatch or silence.

#include <cstdint>
#include <string>
#include <vector>

#include "p3at/hal/team_link.hpp"
#include "p3at/launch_gate/gate_verdict.hpp"

namespace p3at::gate {

enum class AgreementState {
  waiting,   ///< not every teammate has been heard yet
  launch,    ///< every robot voted GO or OVERRIDE for this very mission: start
  no_go,     ///< this robot or a teammate said NO-GO
  mismatch,  ///< a teammate verified a different mission or different models
  silent,    ///< a teammate said nothing within the timeout
};
/// "waiting", "launch", "no-go", "mismatch", "silent".
const char* to_string(AgreementState state);

struct Agreement {
  AgreementState state = AgreementState::waiting;
  std::string reason;                       ///< one line, for logs and refusals
  std::vector<std::string> silent;          ///< teammates not heard from (silent)
  std::vector<gate::GateVerdict> team;       ///< the verdicts decided on: own first, then teammates by roster
};

class TeamAgreement {
 public:
  /// `own.robot` must be set; `roster` lists every robot of the team (own included).
  TeamAgreement(gate::GateVerdict own, std::vector<std::string> roster, std::int64_t start_us, std::int64_t timeout_us);

  /// Decides from `teammates` (the link's latest verdict of each) at `now_us`.
  const Agreement& update(std::int64_t now_us, const std::vector<gate::GateVerdict>& teammates);

  const Agreement& current() const { return agreement_; }
  bool decided() const { return agreement_.state != AgreementState::waiting; }
  const gate::GateVerdict& own() const { return own_; }

 private:
  void decide(AgreementState state, std::string reason);

  gate::GateVerdict own_;
  std::vector<std::string> teammates_;  ///< roster without own, in roster order
  std::int64_t start_us_;
  std::int64_t timeout_us_;
  Agreement agreement_;
};

}  // namespace p3at::gate
