// vipars: verify, simulate and validate multirobot missions (after VIPARS,
// Lyons, Arkin et al.). `vipars --help` and `vipars SUBCOMMAND --help`.

#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"vipars: performance guarantees for multirobot missions.\n"
               "Translate a mission to PARS, verify it against its criteria, gate a launch on the verdict, "
               "simulate it in fast time, calibrate robot models from data, validate the verification "
               "with simulated trials (sharded over a cluster and merged) and report verification against validation."};
  app.require_subcommand(1);
  int exit_status = p3at::vipars::kExitOk;
  p3at::vipars::register_translate(app, exit_status);
  p3at::vipars::register_verify(app, exit_status);
  p3at::vipars::register_gate(app, exit_status);
  p3at::vipars::register_simulate(app, exit_status);
  p3at::vipars::register_calibrate(app, exit_status);
  p3at::vipars::register_validate(app, exit_status);
  p3at::vipars::register_merge(app, exit_status);
  p3at::vipars::register_report(app, exit_status);
  p3at::vipars::register_generate(app, exit_status);
  p3at::vipars::register_crosscheck(app, exit_status);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print and succeed; any other bad flag is bad input (exit 2).
    return app.exit(e) == 0 ? p3at::vipars::kExitOk : p3at::vipars::kExitBadInput;
  }
  return exit_status;
}
