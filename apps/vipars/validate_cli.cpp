// vipars validate MISSION --world FILE --trials N [--jobs J] [--seed S]
//   [--tmax S] [--rmax M] [--tmax-range A:B:STEP] [--rmax-range A:B:STEP]
//   [--region-low P] [--region-high P] [--timeout S] [--json] [--csv FILE]
//   [--shard I/N --part FILE]
// The flags; the campaign is p3at_validation's run_validate().

#include <memory>

#include "commands.hpp"
#include "p3at/validation/validate.hpp"

namespace p3at::vipars {

void register_validate(CLI::App& app, int& exit_status) {
  auto o = std::make_shared<ValidateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate", "Validation campaign: N fast-time runs of the real executive, empirical P(success) with 95% CIs");
  cmd->add_option("mission", o->mission_file, "Mission file (YAML)")->required();
  cmd->add_option("--world", o->world_file, "World file: walls, robots' error models, radio")->required();
  cmd->add_option("--trials", o->trials, "Number of independent runs")->required();
  cmd->add_option("--jobs", o->jobs, "Worker threads (default: all cores); the results do not depend on it");
  cmd->add_option("--seed", o->seed, "Campaign seed; run i's seed is the i-th SplitMix64 output from it")
      ->capture_default_str();
  CLI::Option* tmax = cmd->add_option("--tmax", o->tmax_s, "Time bound in seconds (default: the mission's tmax_s)");
  CLI::Option* rmax = cmd->add_option("--rmax", o->rmax_m, "Radius bound in metres (default: the mission's rmax_m)");
  cmd->add_option("--tmax-range", o->tmax_range, "Grid axis A:B:STEP in seconds (B included when on a step)");
  cmd->add_option("--rmax-range", o->rmax_range, "Grid axis A:B:STEP in metres (B included when on a step)");
  cmd->add_option("--region-low", o->region_low, "Grid cells with P(success) below this are 'unsuccessful'")
      ->capture_default_str();
  cmd->add_option("--region-high", o->region_high, "Grid cells with P(success) at or above this are 'successful'")
      ->capture_default_str();
  cmd->add_option("--timeout", o->timeout_s, "Simulated seconds before a run counts as failed (timeout)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print the result as JSON (the keys of `vipars verify --json`)");
  cmd->add_option("--csv", o->csv_file, "Write one row per run to this CSV file");
  cmd->add_option("--shard", o->shard,
                  "Make only shard I of N's runs (I from 0), with the seeds they have in the whole campaign");
  cmd->add_option("--part", o->part_file, "With --shard: write the shard's part here, for vipars merge");
  cmd->callback([o, tmax, rmax, &exit_status] {
    o->tmax_given = tmax->count() > 0;
    o->rmax_given = rmax->count() > 0;
    exit_status = run_validate(*o);
  });
}

}  // namespace p3at::vipars
