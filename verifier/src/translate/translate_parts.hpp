#pragma once
// The pieces of the translation (translate.cpp assembles them): the Mission
// process with one definition per FSA state, and the model processes (robot,
// sensor/environment, communication) with their instances in Sys.

#include <optional>
#include <string>
#include <vector>

#include "p3at/mission/mission.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::detail {

/// Mission's in and out ports: every robot's odometry and obstacles, every
/// message's delivery and acknowledgement / every robot's velocity, every put.
std::vector<std::string> mission_in_ports(const mission::Mission& mission);
std::vector<std::string> mission_out_ports(const mission::Mission& mission);

/// Mission = the robots' initial states in parallel, then one definition per state.
std::vector<pars::Definition> mission_definitions(const mission::Mission& mission);

/// The values the models give (nullptr: symbols).
pars::Definition robot_template();
pars::Term robot_instance(const mission::RobotSpec& robot, const RobotModel* model);
pars::Definition environment_definition(const mission::Mission& mission);
pars::Term environment_instance(const mission::Mission& mission, const Environment* environment);
/// Only for a mission with messages.
pars::Definition comm_definition(const mission::Mission& mission);
pars::Term comm_instance(const mission::Mission& mission, const CommModel* comm);
/// The Sys comment: what the instances' parameters are.
std::string system_comment(const mission::Mission& mission, const Models* models);

}  // namespace p3at::verifier::detail
