#pragma once
// The exit statuses of `vipars`, shared by every subcommand and by the
// libraries whose runs they are (validation, report, calibration_rig), which
// return them so that each subcommand stays argument parsing and a call.

namespace p3at::vipars {

inline constexpr int kExitOk = 0;
inline constexpr int kExitNoGo = 1;      ///< verify / gate: the mission does not meet its criteria
inline constexpr int kExitBadInput = 2;  ///< unreadable or invalid mission, world, models, flags
inline constexpr int kExitFailed = 3;    ///< the command could not complete (e.g. runs failed)
/// verify / gate: the probabilities say GO but the model does not vouch for
/// the mission (an unvouched approximation, docs/verifier.md): not GO.
inline constexpr int kExitCannotEvaluate = 3;

}  // namespace p3at::vipars
