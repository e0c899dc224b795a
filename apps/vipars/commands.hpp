#pragma once
// Each vipars subcommand registers its options and, when chosen, runs and
// sets the process exit status.

#include <CLI/CLI.hpp>

#include "p3at/common/vipars_exit.hpp"

namespace p3at::vipars {

void register_simulate(CLI::App& app, int& exit_status);
void register_translate(CLI::App& app, int& exit_status);
void register_verify(CLI::App& app, int& exit_status);
void register_gate(CLI::App& app, int& exit_status);
void register_calibrate(CLI::App& app, int& exit_status);
void register_validate(CLI::App& app, int& exit_status);
void register_merge(CLI::App& app, int& exit_status);
void register_report(CLI::App& app, int& exit_status);
void register_generate(CLI::App& app, int& exit_status);
void register_crosscheck(CLI::App& app, int& exit_status);

}  // namespace p3at::vipars
