#pragma once
// Each vipars subcommand registers its options and, when chosen, runs and
// sets the process exit status.

#include <CLI/CLI.hpp>

namespace p3at::vipars {

/// Exit statuses shared by every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitNoGo = 1;      ///< verify / gate: the mission does not meet its criteria
inline constexpr int kExitBadInput = 2;  ///< unreadable or invalid mission, world, models, flags
inline constexpr int kExitFailed = 3;    ///< the command could not complete (e.g. runs failed)
/// verify / gate: the probabilities say GO but the model does not vouch for
/// the mission (an unvouched approximation, docs/verifier.md): not GO.
inline constexpr int kExitCannotEvaluate = 3;

void register_simulate(CLI::App& app, int& exit_status);
void register_translate(CLI::App& app, int& exit_status);
void register_verify(CLI::App& app, int& exit_status);
void register_gate(CLI::App& app, int& exit_status);
void register_calibrate(CLI::App& app, int& exit_status);
void register_validate(CLI::App& app, int& exit_status);
void register_report(CLI::App& app, int& exit_status);


}  // namespace p3at::vipars
