#pragma once
// mission_exec's configuration steps, each returning an error message a person
// can act on (exit code 2: bad input). No I/O beyond reading files. (The
// mission itself is loaded by the launch gate's pre-launch check, which hashes
// and parses the very same bytes.)

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/hal/team_key.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/protocols/mission/mission.hpp"

namespace p3at::mission_exec {

/// Index of `robot_name` in the mission; the error lists the robots it has.
Result<std::size_t> find_robot(const mission::Mission& mission, const std::string& robot_name);

/// The team key: from `flag_path` if given, else from the file named by
/// $P3AT_TEAM_KEY (`env_path`), else an error saying how to make one.
Result<hal::TeamKey> load_key(const std::optional<std::string>& flag_path, const char* env_path);

/// Opens the LCM team link for `robot_index`: roster = the mission's robots,
/// mission id = the mission's name.
Result<std::unique_ptr<hal::TeamLink>> open_team_link(const mission::Mission& mission, std::size_t robot_index,
                                                      const std::string& lcm_url, const hal::TeamKey& key);

}  // namespace p3at::mission_exec
