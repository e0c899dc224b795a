#include "p3at/verifier/translate.hpp"

#include <utility>

#include "translate/translate_parts.hpp"

namespace p3at::verifier {

namespace {

pars::Program assemble(const mission::Mission& mission, const Models* models) {
  pars::Program program;
  program.definitions = detail::mission_definitions(mission);
  program.definitions.push_back(detail::robot_template());
  program.definitions.push_back(detail::environment_definition(mission));
  const bool messages = !mission.messages.empty();
  if (messages) program.definitions.push_back(detail::comm_definition(mission));

  pars::Definition sys;
  sys.name = "Sys";
  sys.comment = detail::system_comment(mission, models);
  std::vector<pars::Term> components;
  components.push_back(pars::process("Mission", {}, detail::mission_in_ports(mission), detail::mission_out_ports(mission)));
  for (const mission::RobotSpec& robot : mission.robots) {
    const RobotModel* model = nullptr;
    if (models != nullptr) {
      for (const RobotModel& candidate : models->robots) {
        if (candidate.name == robot.name) model = &candidate;
      }
    }
    components.push_back(detail::robot_instance(robot, model));
  }
  components.push_back(detail::environment_instance(mission, models != nullptr ? &models->environment : nullptr));
  if (messages) components.push_back(detail::comm_instance(mission, models != nullptr ? &models->comm : nullptr));
  sys.body = pars::parallel(std::move(components));
  program.definitions.push_back(std::move(sys));
  return program;
}

}  // namespace

pars::Program translate(const mission::Mission& mission) { return assemble(mission, nullptr); }

Result<pars::Program> translate(const mission::Mission& mission, const Models& models) {
  for (const mission::RobotSpec& robot : mission.robots) {
    bool found = false;
    for (const RobotModel& model : models.robots) found = found || model.name == robot.name;
    if (!found) {
      std::string known;
      for (const RobotModel& model : models.robots) known += (known.empty() ? "" : ", ") + model.name;
      return make_error(Error::Code::not_found, "no model for robot '" + robot.name + "' in " +
                                                    (models.source.empty() ? "the models" : models.source) +
                                                    " (it describes " + (known.empty() ? "no robots" : known) + ")");
    }
  }
  return assemble(mission, &models);
}

}  // namespace p3at::verifier
