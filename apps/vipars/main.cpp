// vipars: verify, simulate and validate multirobot missions (after VIPARS,
// Lyons, Arkin et al.). `vipars --help` and `vipars SUBCOMMAND --help`.

#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"vipars: performance guarantees for multirobot missions.\n"
               "Simulate a mission in fast time against simulated P3-ATs; later: translate it to PARS, "
               "verify it, calibrate models, validate the verification, and gate a launch."};
  app.require_subcommand(1);
  int exit_status = p3at::vipars::kExitOk;
  p3at::vipars::register_simulate(app, exit_status);
  CLI11_PARSE(app, argc, argv);
  return exit_status;
}
