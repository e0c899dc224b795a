#pragma once
/// Loading a mission file (YAML, schema in docs/mission-format.md). Loading is
/// configuration, not the control path, so a bad mission throws MissionError,
/// which names the offending node as file:line:column and says what was expected.

#include <stdexcept>
#include <string>
#include <string_view>

#include "p3at/common/located_error.hpp"
#include "p3at/mission/mission.hpp"

namespace p3at::mission {

/// A mission that cannot be loaded. what() is the whole one-line message,
/// "file:line:column: detail" (or "file: detail" when there is no position).
class MissionError : public LocatedError {
 public:
  using LocatedError::LocatedError;
};

/// Parses and validates a mission from YAML text. `source_name` is used only
/// in error messages (normally the file's path). Returns a fully resolved,
/// valid Mission, or throws MissionError for the first problem found.
Mission parse_mission(std::string_view yaml_text, const std::string& source_name);

/// Reads the file at `path` and parses it with parse_mission. Throws
/// MissionError (with no position) if the file cannot be read.
Mission load_mission_file(const std::string& path);

}  // namespace p3at::mission
