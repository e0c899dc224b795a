#pragma once
// A world's walls: the `walls:` list of a world file, each wall
// [x0, y0, x1, y1] in metres. The one reading of it, shared by the
// simulator's world loader (sim_hal) and the verifier's robot models
// (`environment: walls` and `walls_from: <world file>`), which cannot link
// each other: a world the simulator accepts has the walls the verifier sees.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "p3at/common/yaml_reader.hpp"

namespace p3at::yaml_reader {

/// One wall: the segment from (x0_m, y0_m) to (x1_m, y1_m).
struct WallSegment {
  double x0_m = 0.0, y0_m = 0.0, x1_m = 0.0, y1_m = 0.0;
};

/// The walls of `list`, which must be a list (else fails at `mark`); `label`
/// names it in messages ("walls", "environment.walls"). Each wall is 4
/// finite numbers within +-1e6 m ('walls[0][3]' named in messages) with two
/// distinct end points.
std::vector<WallSegment> read_walls(const Source& src, const YAML::Node& list, const YAML::Mark& mark,
                                    const std::string& label);

}  // namespace p3at::yaml_reader
