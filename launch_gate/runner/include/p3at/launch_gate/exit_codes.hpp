#pragma once
// mission_exec's exit statuses (also in `mission_exec --help`, docs/executive.md
// and docs/launch-gate.md). The gate's refusals each have their own, so a
// script or an operator can tell why no robot moved.

namespace p3at::mission_exec {

inline constexpr int kExitOk = 0;             ///< the FSA reached a final state
inline constexpr int kExitBadInput = 2;       ///< arguments, mission, models, robot name, URL, team key
inline constexpr int kExitAborted = 3;        ///< aborted during the mission, or could not start
inline constexpr int kExitGateNoGo = 4;       ///< launch gate: this robot or a teammate said NO-GO
inline constexpr int kExitGateMismatch = 5;   ///< launch gate: a teammate verified a different mission hash
inline constexpr int kExitGateSilent = 6;     ///< launch gate: a teammate sent no verdict within --gate-timeout
inline constexpr int kExitGateCannotRun = 7;  ///< launch gate: no models file, or the verifier cannot evaluate
inline constexpr int kExitGateInDoubt = 8;    ///< launch gate: committed, but the teammates' commitments never came

inline constexpr const char* kExitHelp =
    "Exit status:\n"
    "  0  finished: the FSA reached a final state\n"
    "  2  bad input: arguments, mission, models, criterion file, robot name, URL, team key\n"
    "  3  aborted (link loss, safety stop, teammate abort, re-verification below the abort threshold,\n"
    "     signal), or could not start\n"
    "  launch gate refused, no robot moved:\n"
    "  4  NO-GO: this robot's verdict or a teammate's\n"
    "  5  a teammate verified a different mission hash\n"
    "  6  a teammate sent no verdict within --gate-timeout\n"
    "  7  the gate cannot run: no models file, or the verifier cannot evaluate the mission\n"
    "  8  in doubt: this robot committed to launch but never heard its teammates commit; it did not move,\n"
    "     a teammate may have (a lost message; docs/launch-gate.md)";

}  // namespace p3at::mission_exec
