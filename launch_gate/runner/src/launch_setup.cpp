#include "launch_setup.hpp"

#include <utility>

#include "p3at/hal/lcm_team_link.hpp"
#include "p3at/hal/team_protocol.hpp"

namespace p3at::mission_exec {

Result<std::size_t> find_robot(const mission::Mission& mission, const std::string& robot_name) {
  if (const std::optional<std::size_t> index = mission.find_robot(robot_name)) return *index;
  std::string names;
  for (const mission::RobotSpec& r : mission.robots) names += (names.empty() ? "" : ", ") + r.name;
  return make_error(Error::Code::not_found,
                    "robot '" + robot_name + "' is not in mission '" + mission.name + "' (its robots: " + names + ")");
}

Result<hal::TeamKey> load_key(const std::optional<std::string>& flag_path, const char* env_path) {
  std::string path;
  if (flag_path) {
    path = *flag_path;
  } else if (env_path != nullptr && *env_path != '\0') {
    path = env_path;
  } else {
    return make_error(Error::Code::invalid_argument,
                      "no team key: pass --team-key FILE or set P3AT_TEAM_KEY=FILE. Make a key once with "
                      "`p3at_team_key FILE` and copy that file to every robot of the team");
  }
  return hal::load_team_key(path);
}

Result<std::unique_ptr<hal::TeamLink>> open_team_link(const mission::Mission& mission, std::size_t robot_index,
                                                      const std::string& lcm_url, const hal::TeamKey& key) {
  hal::TeamLinkConfig config;
  config.mission_id = mission.name;
  config.self = mission.robots.at(robot_index).name;
  for (const mission::RobotSpec& r : mission.robots) config.roster.push_back(r.name);
  return hal::open_lcm_team_link(lcm_url, std::move(config), key);
}

}  // namespace p3at::mission_exec
