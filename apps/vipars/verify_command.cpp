// vipars verify MISSION --models FILE [--tmax S] [--rmax M] [--threshold P]
//   [--tmax-range A:B:STEP] [--rmax-range A:B:STEP] [--criterion FILE]... [--json]
// The seed paper's verification (docs/verifier.md): probabilities that the
// mission meets its criteria, from the mission and the robot models alone.

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "p3at/validation/range_arg.hpp"
#include "p3at/validation/verify_output.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::vipars {
namespace {

struct VerifyFlags {
  std::string mission_file;
  std::string models_file;
  std::optional<double> tmax_s, rmax_m, threshold;
  std::string tmax_range, rmax_range;
  std::vector<std::string> criteria;
  double region_low = 0.05, region_high = 0.95;
  bool json = false;
};

int run_verify(const VerifyFlags& f) {
  std::optional<mission::Mission> mission;
  std::optional<verifier::Models> models;
  try {
    mission = mission::load_mission_file(f.mission_file);
    models = verifier::load_models_file(f.models_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vipars verify: %s\n", e.what());
    return kExitBadInput;
  }
  verifier::VerifyOptions options;
  options.tmax_s = f.tmax_s;
  options.rmax_m = f.rmax_m;
  options.threshold = f.threshold;
  options.region_low = f.region_low;
  options.region_high = f.region_high;
  for (const auto& [text, axis, name] : {std::tuple{f.tmax_range, &options.tmax_grid, "--tmax-range"},
                                          std::tuple{f.rmax_range, &options.rmax_grid, "--rmax-range"}}) {
    if (text.empty()) continue;
    Result<std::vector<double>> values = parse_range(text);
    if (!values) {
      std::fprintf(stderr, "vipars verify: %s: %s\n", name, values.error().message.c_str());
      return kExitBadInput;
    }
    *axis = *values;
  }
  Result<verifier::VerifyResult> result = verifier::verify(*mission, *models, options, f.criteria);
  if (!result) {
    std::fprintf(stderr, "vipars verify: %s\n", result.error().message.c_str());
    return kExitBadInput;
  }
  locate_from_file(*result, f.mission_file);
  if (f.json) {
    std::cout << verify_json(*mission, *result).dump(2) << "\n";
  } else {
    std::cout << verify_text(*mission, *result);
  }
  switch (verifier::decision(*result)) {
    case verifier::Decision::go: return kExitOk;
    case verifier::Decision::no_go: return kExitNoGo;
    case verifier::Decision::cannot_evaluate: return kExitCannotEvaluate;
  }
  return kExitFailed;
}

}  // namespace

void register_verify(CLI::App& app, int& exit_status) {
  auto flags = std::make_shared<VerifyFlags>();
  CLI::App* sub = app.add_subcommand(
      "verify",
      "Verify a mission: P(t <= Tmax), P(every robot within Rmax of its goal) and their joint, from the mission "
      "and the robot models (no sampling), and the model's approximations on this mission. Exit 0 = GO, 1 = NO-GO, "
      "2 = bad input, 3 = cannot evaluate (GO by the probabilities, but an approximation the model does not vouch "
      "for; docs/verifier.md).");
  sub->add_option("mission", flags->mission_file, "mission file (YAML, docs/mission-format.md)")->required();
  sub->add_option("--models", flags->models_file, "robot models file (docs/robot-models.md)")->required();
  sub->add_option("--tmax", flags->tmax_s, "Tmax in seconds (default: the mission's criteria)");
  sub->add_option("--rmax", flags->rmax_m, "Rmax in metres (default: the mission's criteria)");
  sub->add_option("--threshold", flags->threshold, "minimum P(success) for GO (default: the mission's)");
  sub->add_option("--tmax-range", flags->tmax_range, "grid of Tmax values A:B:STEP (seconds)");
  sub->add_option("--rmax-range", flags->rmax_range, "grid of Rmax values A:B:STEP (metres)");
  sub->add_option("--criterion", flags->criteria, "extra criterion file (PARS network + constraints, docs/pars.md); repeatable");
  sub->add_option("--region-low", flags->region_low, "grid cells with P below this are high-confidence unsuccessful")
      ->capture_default_str();
  sub->add_option("--region-high", flags->region_high, "grid cells with P at or above this are high-confidence successful")
      ->capture_default_str();
  sub->add_flag("--json", flags->json, "JSON output (keys in docs/verifier.md)");
  sub->callback([flags, &exit_status] { exit_status = run_verify(*flags); });
}

}  // namespace p3at::vipars
