// vipars report --verify FILE.json --validate FILE.json --out DIR [options]
// vipars report MISSION --models FILE --world FILE --trials N
//   --tmax-range A:B:STEP --rmax-range A:B:STEP --out DIR [options]
// The flags; the report is p3at_report's run_report().

#include <memory>

#include "commands.hpp"
#include "p3at/report/make_report.hpp"

namespace p3at::vipars {

void register_report(CLI::App& app, int& exit_status) {
  auto f = std::make_shared<ReportFlags>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Verification vs. validation report: figures (PNG, SVG) of the seed paper's Figs. 9-13 and the error map, "
      "errors.json and index.html. Exit 0 = every max |verify - validate| within its bound (0.05 over P(t), 0.05 over "
      "P(r), 0.08 over the joint surface), 1 = a bound exceeded, 2 = bad input, 3 = failed (e.g. gnuplot).");
  cmd->add_option("mission", f->mission_positional,
                  "Mission file: run verify and validate here (needs --models, --world, --trials and both ranges)");
  cmd->add_option("--verify", f->verify_file, "`vipars verify --json` output, with a grid");
  cmd->add_option("--validate", f->validate_file, "`vipars validate --json` output, on the same grid");
  cmd->add_option("--out", f->out_dir, "Folder to write the report into (created if missing)")->required();
  cmd->add_option("--mission", f->mission_file, "The mission file the documents came from (hashed into the page)");
  cmd->add_option("--models", f->models_file, "Robot models file (hashed; required with MISSION)");
  cmd->add_option("--world", f->world_file, "World file (hashed; required with MISSION)");
  cmd->add_option("--title", f->title, "Title of the page and figures (default: the mission's name)");
  cmd->add_option("--verify-command", f->verify_command, "The command that made --verify's file, for the page");
  cmd->add_option("--validate-command", f->validate_command, "The command that made --validate's file, for the page");
  cmd->add_option("--trials", f->trials, "With MISSION: validation runs");
  cmd->add_option("--jobs", f->jobs, "With MISSION: validation threads (default: all cores)");
  cmd->add_option("--seed", f->seed, "With MISSION: the campaign seed")->capture_default_str();
  cmd->add_option("--timeout", f->timeout_s, "With MISSION: simulated seconds before a run fails")
      ->capture_default_str();
  cmd->add_option("--tmax", f->tmax_s, "With MISSION: the criterion's Tmax (default: the mission's)");
  cmd->add_option("--rmax", f->rmax_m, "With MISSION: the criterion's Rmax (default: the mission's)");
  cmd->add_option("--tmax-range", f->tmax_range, "With MISSION: grid axis A:B:STEP in seconds");
  cmd->add_option("--rmax-range", f->rmax_range, "With MISSION: grid axis A:B:STEP in metres");
  cmd->add_option("--region-low", f->region_low, "Below this probability: high-confidence unsuccessful")
      ->capture_default_str();
  cmd->add_option("--region-high", f->region_high, "At or above this probability: high-confidence successful")
      ->capture_default_str();
  cmd->add_option("--rmax-slices", f->rmax_slices, "Fig. 12's Rmax values, e.g. 1.8,2,2.2 (default: 4 chosen)")
      ->delimiter(',');
  cmd->add_option("--tmax-slices", f->tmax_slices, "Fig. 13's Tmax values, e.g. 190,195,200 (default: 4 chosen)")
      ->delimiter(',');
  cmd->add_option("--gnuplot", f->gnuplot, "gnuplot program to render with")->capture_default_str();
  cmd->add_flag("--no-plots", f->no_plots, "Write the data files and scripts but do not run gnuplot");
  cmd->callback([f, &exit_status] { exit_status = run_report(*f); });
}

}  // namespace p3at::vipars
