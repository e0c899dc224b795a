// vipars translate MISSION [--models FILE] [--connections] [--success]
// Prints the mission's PARS program (docs/pars.md): the Mission process with
// every robot's FSA, the robot, sensor/environment and communication models,
// and Sys. --models fills in the models' values; --connections adds the port
// graph and flow function as comments; --success prints the eq. (7) criterion
// file instead of the program.

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/translate.hpp"

namespace p3at::vipars {
namespace {

struct TranslateOptions {
  std::string mission_file;
  std::string models_file;
  bool connections = false;
  bool success = false;
};

// Each line of `text` as a '#' comment.
std::string as_comment(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    out += line.empty() ? "#\n" : "# " + line + "\n";
    start = end + 1;
  }
  return out;
}

int translate(const TranslateOptions& o) {
  std::optional<mission::Mission> mission;
  std::optional<verifier::Models> models;
  try {
    mission = mission::load_mission_file(o.mission_file);
    if (!o.models_file.empty()) models = verifier::load_models_file(o.models_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vipars translate: %s\n", e.what());
    return kExitBadInput;
  }
  if (o.success) {
    const verifier::Criterion c =
        verifier::success_criterion(*mission, mission->criteria.tmax_s, mission->criteria.rmax_m);
    std::printf("# The seed paper's eq. (7) for mission '%s': every robot done by Tmax and within Rmax of its goal.\n%s",
                mission->name.c_str(), verifier::to_string(c).c_str());
    return kExitOk;
  }
  verifier::pars::Program program;
  if (models) {
    auto translated = verifier::translate(*mission, *models);
    if (!translated) {
      std::fprintf(stderr, "vipars translate: %s\n", translated.error().message.c_str());
      return kExitBadInput;
    }
    program = std::move(translated.value());
  } else {
    program = verifier::translate(*mission);
  }
  std::printf("# PARS program of mission '%s' (%s), written by vipars translate; docs/pars.md describes it.\n\n%s",
              mission->name.c_str(), o.mission_file.c_str(), verifier::pars::to_string(program).c_str());
  if (o.connections) {
    const auto composed = verifier::compose_system(program);
    if (!composed) {
      std::fprintf(stderr, "vipars translate: %s\n", composed.error().message.c_str());
      return kExitFailed;
    }
    std::printf("\n%s", as_comment(verifier::to_string(*composed)).c_str());
  }
  return kExitOk;
}

}  // namespace

void register_translate(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<TranslateOptions>();
  CLI::App* cmd = app.add_subcommand("translate", "Print a mission's PARS program (its FSAs, the models and Sys)");
  cmd->add_option("mission", options->mission_file, "Mission file (YAML)")->required();
  cmd->add_option("--models", options->models_file, "Robot-models file: print the models' values instead of symbols");
  cmd->add_flag("--connections", options->connections,
                "Also print Sys's port connections and flow function (as comments)");
  cmd->add_flag("--success", options->success,
                "Print the mission's success criterion (the paper's eq. 7) as a criterion file instead");
  cmd->callback([options, &exit_status] { exit_status = translate(*options); });
}

}  // namespace p3at::vipars
