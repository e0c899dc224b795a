// The pieces of YAML reading every reader shares (common/yaml).
#include <doctest/doctest.h>

#include <limits>
#include <string>

#include "p3at/common/located_error.hpp"
#include "p3at/common/yaml_document.hpp"
#include "p3at/common/yaml_reader.hpp"

using namespace p3at;

namespace {
struct TestError : LocatedError {
  using LocatedError::LocatedError;
};
}  // namespace

TEST_CASE("Source::fail throws the reader's error at the node, 1-based") {
  const YAML::Node root = yaml_document::load_single("a: 1\nb: [x, 2]\n", "empty");
  const yaml_reader::SourceOf<TestError> src("t.yaml");
  try {
    src.fail(root["b"].Mark(), "expected a mapping");
    FAIL("no throw");
  } catch (const TestError& e) {
    CHECK(std::string(e.what()) == "t.yaml:2:4: expected a mapping");
  }
  try {
    src.fail(YAML::Mark::null_mark(), "cannot read");
    FAIL("no throw");
  } catch (const TestError& e) {
    CHECK(std::string(e.what()) == "t.yaml: cannot read");
  }
  CHECK(yaml_reader::position(root["b"].Mark()) == "2:4");
}

TEST_CASE("describe says what a node is; may_be_number tells a quoted \"2\" from 2") {
  const YAML::Node root = yaml_document::load_single("n: 2\nq: \"2\"\nl: [1]\nm: {}\nz: ~\nt: !!int 3\n", "empty");
  CHECK(yaml_reader::describe(root["n"]) == "'2'");
  CHECK(yaml_reader::describe(root["q"]) == "the quoted string \"2\"");
  CHECK(yaml_reader::describe(root["l"]) == "a list");
  CHECK(yaml_reader::describe(root["m"]) == "a mapping");
  CHECK(yaml_reader::describe(root["z"]) == "null");
  CHECK(yaml_reader::may_be_number(root["n"]));
  CHECK_FALSE(yaml_reader::may_be_number(root["q"]));
  CHECK(yaml_reader::may_be_number(root["t"]));
}

TEST_CASE("Range: open and closed ends, described with the shortest numbers") {
  const yaml_reader::Range r{0.0, 1.0, true, false};
  CHECK_FALSE(r.contains(0.0));
  CHECK(r.contains(1.0));
  CHECK(r.describe("p") == "0 < p <= 1");
  CHECK(yaml_reader::Range{0.1, 2.5}.describe("x") == "0.1 <= x <= 2.5");
  // One infinite end (the world file's "> 0" scales): only the finite bound is named.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const yaml_reader::Range positive{0.0, kInf, true, false};
  CHECK(positive.contains(1e300));
  CHECK_FALSE(positive.contains(0.0));
  CHECK(positive.describe("s") == "s > 0");
  CHECK(yaml_reader::Range{-1.0, kInf}.describe("e") == "e >= -1");
  CHECK(yaml_reader::Range{-kInf, 2.0, false, true}.describe("v") == "v < 2");
}
