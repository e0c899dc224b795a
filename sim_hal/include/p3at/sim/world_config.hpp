#pragma once
/// The world file (docs/simulator.md): walls, robots and every error parameter.
/// Loading is configuration, not control path: errors throw WorldFileError,
/// whose message names file:line:column and what was expected.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/common/located_error.hpp"
#include "p3at/sim/geometry.hpp"
#include "p3at/sim/radio.hpp"
#include "p3at/sim/robot_model.hpp"

namespace p3at::sim {

struct WorldConfig {
  std::vector<Segment> walls;
  std::vector<RobotConfig> robots;
  RadioParams radio;                  ///< the team radio of fast-time runs (`radio:`)
  std::optional<std::uint64_t> seed;  ///< the file's `seed:`, if any (--seed overrides)
};

/// A world file that cannot be used: the project's located error (common/),
/// what() one line, "FILE:LINE:COLUMN: what was expected" ("FILE: ..." when
/// there is no position, as for a file that cannot be opened).
class WorldFileError : public LocatedError {
 public:
  using LocatedError::LocatedError;
};

/// Parses world YAML. `source_name` names the text in messages (a file path).
/// Unknown keys, missing required fields, wrong types, out-of-range values,
/// duplicate robot names or ports and robots starting inside a wall or another
/// robot are all errors.
WorldConfig parse_world(const std::string& yaml_text, const std::string& source_name);

/// Reads and parses a world file. An unreadable file is a WorldFileError too.
WorldConfig load_world_file(const std::string& path);

/// The world used when no file is given: one P3-AT "robot1" at the origin, no walls.
WorldConfig default_world();

}  // namespace p3at::sim
