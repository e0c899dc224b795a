#include "p3at/common/world_walls.hpp"

#include <array>
#include <cmath>
#include <cstddef>

namespace p3at::yaml_reader {
namespace {

// Wide enough for any site, narrow enough that no later arithmetic overflows.
constexpr Range kCoordinate{-1e6, 1e6};
// Shorter than this is a point, not a wall (a ray cast would divide by its length).
constexpr double kMinLengthM = 1e-6;

std::string indexed(const std::string& label, std::size_t i) { return label + "[" + std::to_string(i) + "]"; }

// The element's own mark, or the list's for a null element.
YAML::Mark element_mark(const YAML::Node& list, const YAML::Node& element) {
  return element.IsNull() ? list.Mark() : element.Mark();
}

}  // namespace

std::vector<WallSegment> read_walls(const Source& src, const YAML::Node& list, const YAML::Mark& mark,
                                    const std::string& label) {
  if (!list.IsSequence()) src.fail(mark, "expected a list for '" + label + "', got " + describe(list));
  std::vector<WallSegment> walls;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    const std::string wall_label = indexed(label, i);
    const YAML::Mark at = element_mark(list, node);
    if (!node.IsSequence() || node.size() != 4) {
      src.fail(at, "expected a wall [x0, y0, x1, y1] (4 numbers, metres) for '" + wall_label + "', got " +
                       (node.IsSequence() ? "a list of " + std::to_string(node.size()) : describe(node)));
    }
    std::array<double, 4> v{};
    for (std::size_t j = 0; j < 4; ++j) {
      const YAML::Node element = node[j];
      v[j] = read_number(src, element, element_mark(node, element), indexed(wall_label, j), kCoordinate);
    }
    if (std::hypot(v[2] - v[0], v[3] - v[1]) < kMinLengthM) {
      src.fail(at, "expected a wall with two distinct end points for '" + wall_label + "'");
    }
    walls.push_back(WallSegment{v[0], v[1], v[2], v[3]});
  }
  return walls;
}

}  // namespace p3at::yaml_reader
