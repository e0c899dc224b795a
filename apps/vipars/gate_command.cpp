// vipars gate MISSION [--models FILE] [--tmax S] [--rmax M] [--threshold P] [--criterion FILE]...
// The launch gate's pre-launch check on the operator's station: the very
// check every robot's mission_exec makes before moving (the launch gate
// library's pre_launch_check(), docs/launch-gate.md), printed as GO / NO-GO
// with the probabilities, the failed criteria, the mission's content hash
// (the robots must report the same one) and the decision time.

#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "p3at/launch_gate/check_report.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"

namespace p3at::vipars {
namespace {

// The flags fill the pre-launch check's request directly, as mission_exec's do.
int run_gate(const gate::CheckRequest& request) {
  const gate::CheckReport report = gate::pre_launch_check(request, gate::verifier_source());
  if (report.accepted_unvouched) {
    // Logged where the operator sees it, as mission_exec logs it on every robot.
    std::fprintf(stderr, "vipars gate: event=gate-accept-unvouched unvouched=%s p_joint=%.4f threshold=%.4f "
                         "operator=--accept-unvouched\n",
                 verifier::unvouched_kinds(report.result.approximations).c_str(), report.result.p_joint,
                 report.result.threshold);
  }
  switch (report.status) {
    case gate::CheckStatus::go:
    case gate::CheckStatus::no_go:
      std::fputs(gate::format_check(report).c_str(), stdout);
      return report.status == gate::CheckStatus::go ? kExitOk : kExitNoGo;
    case gate::CheckStatus::bad_input:
    case gate::CheckStatus::no_models:
      std::fprintf(stderr, "vipars gate: %s\n", report.error.c_str());
      return kExitBadInput;
    case gate::CheckStatus::cannot_run:
    case gate::CheckStatus::cannot_evaluate:
      std::fputs(gate::format_check(report).c_str(), stdout);
      return kExitCannotEvaluate;
  }
  return kExitFailed;
}

}  // namespace

void register_gate(CLI::App& app, int& exit_status) {
  auto flags = std::make_shared<gate::CheckRequest>();
  CLI::App* sub = app.add_subcommand(
      "gate",
      "The launch gate's check, before anything is deployed: the same verification every robot makes before it "
      "moves (docs/launch-gate.md), as a clear GO / NO-GO with the probabilities and the mission's content hash. "
      "Exit 0 = GO, 1 = NO-GO, 2 = bad input (unreadable mission, models or flags; no models file), "
      "3 = the verifier cannot evaluate the mission with these models (it cannot run, or the mission has an "
      "approximation the model does not vouch for: docs/verifier.md; --accept-unvouched to launch anyway). An "
      "unvouched approximation the mission file shows is refused in milliseconds, without evaluating the mission.");
  sub->add_option("mission", flags->mission_path, "mission file (YAML, docs/mission-format.md)")->required();
  sub->add_option("--models", flags->models_path,
                  "robot models file (docs/verifier.md); default: models.yaml beside the mission file, as on the "
                  "robots");
  sub->add_option("--tmax", flags->options.tmax_s, "override the mission's Tmax (seconds)")->check(CLI::PositiveNumber);
  sub->add_option("--rmax", flags->options.rmax_m, "override the mission's Rmax (metres)")->check(CLI::PositiveNumber);
  sub->add_option("--threshold", flags->options.threshold, "override the mission's launch threshold P")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_option("--criterion", flags->criteria_files, "extra criterion file (PARS, docs/verifier.md); repeatable");
  sub->add_flag("--accept-unvouched", flags->accept_unvouched,
                "Operator's decision: a mission whose approximations the model does not vouch for is evaluated, and "
                "is GO if its probabilities say GO (logged; the robots publish it as OVERRIDE). Without it such a "
                "mission is cannot-evaluate (exit 3), refused before it is even evaluated when the mission file "
                "shows the approximation");
  sub->callback([flags, &exit_status] { exit_status = run_gate(*flags); });
}

}  // namespace p3at::vipars
