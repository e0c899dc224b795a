// The one mapping reader (common/yaml's yaml_map.hpp) in both of its namings,
// and the one reader of a world's walls (world_walls.hpp).
#include <doctest/doctest.h>

#include <string>

#include "p3at/common/located_error.hpp"
#include "p3at/common/world_walls.hpp"
#include "p3at/common/yaml_document.hpp"
#include "p3at/common/yaml_map.hpp"

using namespace p3at;
using yaml_reader::MapReader;

namespace {
struct TestError : LocatedError {
  using LocatedError::LocatedError;
};

// The message a reading of `text` fails with, or "" if it does not.
template <class Read>
std::string error_of(const std::string& text, Read read) {
  const yaml_reader::SourceOf<TestError> src("t.yaml");
  try {
    read(src, yaml_document::load_single(text, "empty"));
  } catch (const TestError& e) {
    return e.what();
  }
  return "";
}

MapReader by_key(const yaml_reader::Source& src, const YAML::Node& root) {
  return MapReader(src, root, YAML::Mark(), "at the top level", "in the test", "key", {"a", "b", "sub"});
}

MapReader by_path(const yaml_reader::Source& src, const YAML::Node& root) {
  return MapReader::at_path(src, root, YAML::Mark(), "", {"a", "b", "sub"});
}

}  // namespace

TEST_CASE("MapReader reads checked values and names keys alone") {
  const yaml_reader::SourceOf<TestError> src("t.yaml");
  const YAML::Node root = yaml_document::load_single("a: +2.5\nb: 7\nsub: {c: x}\n", "empty");
  const MapReader map = by_key(src, root);
  CHECK(map.number("a", {0.0, 3.0}) == 2.5);
  CHECK(map.integer("b", 0, 10) == 7);
  CHECK(map.integer_or("missing", 0, 10, 4) == 4);
  CHECK(map.map("sub", "in sub", {"c"}).string("c") == "x");
  CHECK(map.label("a") == "a");

  CHECK(error_of("a: 1\nz: 2\n", by_key) == "t.yaml:2:1: unknown key 'z' in the test (expected one of a, b, sub)");
  CHECK(error_of("a: 1\na: 2\n", by_key) == "t.yaml:2:1: duplicate key 'a' in the test (first at 1:1)");
  CHECK(error_of("[1]\n", by_key) == "t.yaml:1:1: expected a mapping at the top level, got a list");
  CHECK(error_of("a: 4\n", [](const auto& s, const YAML::Node& n) { by_key(s, n).number("a", {0.0, 3.0}); }) ==
        "t.yaml:1:4: 'a' out of range: 4 (expected 0 <= a <= 3)");
  CHECK(error_of("a: \"2\"\n", [](const auto& s, const YAML::Node& n) { by_key(s, n).number("a", {0.0, 3.0}); }) ==
        "t.yaml:1:4: expected a number for 'a', got the quoted string \"2\"");
  CHECK(error_of("a: 1\n", [](const auto& s, const YAML::Node& n) { by_key(s, n).get("b"); }) ==
        "t.yaml:1:1: missing required key 'b' in the test");
  CHECK(error_of("sub: {d: 1}\n", [](const auto& s, const YAML::Node& n) {
          by_key(s, n).params("sub", "for the sub", {});
        }) == "t.yaml:1:7: unknown parameter 'd' for the sub (it takes none)");
}

TEST_CASE("MapReader::boolean: a plain true or false, nothing else") {
  const yaml_reader::SourceOf<TestError> src("t.yaml");
  CHECK(by_key(src, yaml_document::load_single("a: true\n", "empty")).boolean("a"));
  CHECK_FALSE(by_key(src, yaml_document::load_single("a: false\n", "empty")).boolean("a"));
  const auto read_a = [](const auto& s, const YAML::Node& n) { by_key(s, n).boolean("a"); };
  CHECK(error_of("a: yes\n", read_a) == "t.yaml:1:4: expected true or false for 'a', got 'yes'");
  CHECK(error_of("a: \"true\"\n", read_a) == "t.yaml:1:4: expected true or false for 'a', got the quoted string \"true\"");
  CHECK(error_of("a: [true]\n", read_a) == "t.yaml:1:4: expected true or false for 'a', got a list");
  CHECK(error_of("b: 1\n", read_a) == "t.yaml:1:1: missing required key 'a' in the test");
}

TEST_CASE("MapReader::at_path names keys by their path from the top") {
  CHECK(error_of("z: 1\n", by_path) == "t.yaml:1:1: unknown key 'z' at the top level (expected one of a, b, sub)");
  CHECK(error_of("sub: {c: 1.5}\n", [](const auto& s, const YAML::Node& n) {
          by_path(s, n).map_at("sub", {"c"}).integer("c", 0, 9);
        }) == "t.yaml:1:10: expected an integer for 'sub.c', got '1.5'");
  CHECK(error_of("sub: {c: 12}\n", [](const auto& s, const YAML::Node& n) {
          by_path(s, n).map_at("sub", {"c"}).number("c", {0.0, 9.0});
        }) == "t.yaml:1:10: 'sub.c' out of range: 12 (expected 0 <= c <= 9)");
  CHECK(error_of("sub: 3\n", [](const auto& s, const YAML::Node& n) { by_path(s, n).map_at("sub", {"c"}); }) ==
        "t.yaml:1:6: expected a mapping for 'sub', got '3'");
  CHECK(error_of("sub: {}\n", [](const auto& s, const YAML::Node& n) {
          by_path(s, n).map_at("sub", {"c"}).sequence("c");
        }) == "t.yaml:1:6: missing required key 'c' in sub");
}

TEST_CASE("read_walls: 4 numbers per wall, two distinct end points, located errors") {
  const yaml_reader::SourceOf<TestError> src("w.yaml");
  const YAML::Node root = yaml_document::load_single("walls: [[0, 0, 1, 0], [1, 0, 1, -2.5]]\n", "empty");
  const auto walls = yaml_reader::read_walls(src, root["walls"], root["walls"].Mark(), "walls");
  REQUIRE(walls.size() == 2);
  CHECK(walls[1].x0_m == 1.0);
  CHECK(walls[1].y1_m == -2.5);

  const auto read = [](const yaml_reader::Source& s, const YAML::Node& n) {
    yaml_reader::read_walls(s, n["walls"], n["walls"].Mark(), "walls");
  };
  CHECK(error_of("walls: 3\n", read) == "t.yaml:1:8: expected a list for 'walls', got '3'");
  CHECK(error_of("walls: [[0, 0, 1]]\n", read) ==
        "t.yaml:1:9: expected a wall [x0, y0, x1, y1] (4 numbers, metres) for 'walls[0]', got a list of 3");
  CHECK(error_of("walls: [[0, 0, 1, x]]\n", read) == "t.yaml:1:19: expected a number for 'walls[0][3]', got 'x'");
  CHECK(error_of("walls: [[1, 1, 1, 1]]\n", read) ==
        "t.yaml:1:9: expected a wall with two distinct end points for 'walls[0]'");
  CHECK(error_of("walls: [[0, 0, 2e6, 0]]\n", read) ==
        "t.yaml:1:16: 'walls[0][2]' out of range: 2e6 (expected -1e+06 <= walls[0][2] <= 1e+06)");
}
