// vipars simulate MISSION --world FILE [--runs N] [--seed S] [--csv FILE] [--json]
// The flags; the runs are p3at_validation's run_simulate().

#include <memory>

#include "commands.hpp"
#include "p3at/validation/simulate.hpp"

namespace p3at::vipars {

void register_simulate(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand("simulate", "Run the whole team in fast time against simulated P3-ATs");
  cmd->add_option("mission", options->mission_file, "Mission file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--world", options->world_file, "World file: walls, robots' error models, radio")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--runs", options->runs, "Number of runs")->check(CLI::Range(1, 10'000'000));
  cmd->add_option("--seed", options->seed, "Seed of run 0; run i uses seed+i");
  cmd->add_option("--csv", options->csv_file, "Write one row per run to this CSV file");
  cmd->add_flag("--json", options->json, "Print the runs and a summary as JSON");
  cmd->add_flag("--verbose", options->verbose, "Log every FSA transition (stderr)");
  cmd->add_option("--timeout", options->timeout_s, "Simulated seconds before a run counts as timed out")
      ->check(CLI::Range(1.0, 100000.0));
  cmd->callback([options, &exit_status] { exit_status = run_simulate(*options); });
}

}  // namespace p3at::vipars
