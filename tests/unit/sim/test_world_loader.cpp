// The world file loader: a valid file, defaults and overrides, and errors that
// name file:line:column and what was expected. The loader reads with the
// project's shared YAML vocabulary (common/yaml's MapReader) and throws its
// located error, so the messages below are the missions' and models' forms.

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "p3at/common/located_error.hpp"
#include "p3at/sim/world_config.hpp"
#include "sim_test_util.hpp"

using namespace p3at::sim;
using p3at::sim::test::kDeg;

namespace {

// The message of the WorldFileError that parsing `text` throws ("" if none).
std::string load_error(const std::string& text) {
  try {
    (void)parse_world(text, "w.yaml");
  } catch (const WorldFileError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace

TEST_CASE("a valid world file with every section") {
  const std::string text = R"(seed: 99
walls:
  - [0, 0, 10, 0]
  - [0, 4, 10, 4]
defaults:
  odometry: {left_scale: 1.01, right_scale: 0.99, track_ratio: 1.05, random_trans_per_unit: 0.002, random_rot_per_unit: 0.003}
  sonar: {max_range_m: 4.0, noise_sd_m: 0.02}
  gyro: {bias_degps: 0.1, drift_degps_per_s: 0.001, noise_sd_degps: 0.05}
  limits: {max_trans_vel_mps: 0.5, max_rot_vel_degps: 60, trans_accel_mps2: 0.25, trans_decel_mps2: 0.5, rot_accel_degps2: 90, rot_decel_degps2: 80}
robots:
  - name: alpha
    x_m: 1.5
    y_m: 2.0
    theta_deg: 90
    subclass: p3at
    port: 9000
    odometry:
      right_scale: 1.02
  - name: bravo
    x_m: 3
    y_m: 2
)";
  const WorldConfig w = parse_world(text, "w.yaml");
  REQUIRE(w.seed.has_value());
  CHECK(*w.seed == 99);
  REQUIRE(w.walls.size() == 2);
  CHECK(w.walls[1].a.y == doctest::Approx(4.0));
  CHECK(w.walls[1].b.x == doctest::Approx(10.0));
  REQUIRE(w.robots.size() == 2);
  const RobotConfig& a = w.robots[0];
  CHECK(a.name == "alpha");
  CHECK(a.start.x_m == doctest::Approx(1.5));
  CHECK(a.start.theta_rad == doctest::Approx(90 * kDeg));
  CHECK(a.subclass == "p3at");
  CHECK(a.port == 9000);
  CHECK(a.odometry.left_scale == doctest::Approx(1.01));   // from defaults
  CHECK(a.odometry.right_scale == doctest::Approx(1.02));  // overridden
  CHECK(a.odometry.track_ratio == doctest::Approx(1.05));
  CHECK(a.odometry.random_trans_per_unit == doctest::Approx(0.002));
  CHECK(a.odometry.random_rot_per_unit == doctest::Approx(0.003));
  CHECK(a.sonar.max_range_m == doctest::Approx(4.0));
  CHECK(a.sonar.noise_sd_m == doctest::Approx(0.02));
  REQUIRE(a.gyro.has_value());  // a defaults gyro gives every robot one
  CHECK(a.gyro->bias_degps == doctest::Approx(0.1));
  CHECK(a.gyro->drift_degps_per_s == doctest::Approx(0.001));
  CHECK(a.gyro->noise_sd_degps == doctest::Approx(0.05));
  CHECK(a.gyro->scale_error == doctest::Approx(0.0));
  CHECK(a.limits.max_trans_vel_mps == doctest::Approx(0.5));
  CHECK(a.limits.max_rot_vel_degps == doctest::Approx(60));
  CHECK(a.limits.rot_decel_degps2 == doctest::Approx(80));
  const RobotConfig& b = w.robots[1];
  CHECK(b.subclass == "p3at-sh");  // the default
  CHECK(b.port == -1);
  CHECK(b.start.theta_rad == doctest::Approx(0.0));
  CHECK(b.odometry.right_scale == doctest::Approx(0.99));
  CHECK(b.gyro.has_value());
}

TEST_CASE("without a defaults block the built-in MobileSim-like error model applies") {
  const WorldConfig w = parse_world("robots:\n  - {name: r, x_m: 0, y_m: 0}\n", "w.yaml");
  CHECK(w.walls.empty());
  CHECK_FALSE(w.seed.has_value());
  CHECK(w.robots[0].odometry.random_trans_per_unit == doctest::Approx(0.0075));
  CHECK(w.robots[0].sonar.max_range_m == doctest::Approx(5.0));
  CHECK(w.robots[0].limits.trans_accel_mps2 == doctest::Approx(0.3));
  CHECK(w.robots[0].limits.trans_decel_mps2 == doctest::Approx(0.6));
  CHECK_FALSE(w.robots[0].gyro.has_value());  // a gyro is opt-in
}

TEST_CASE("an unknown key is an error at its line and column, listing the keys expected there") {
  CHECK(load_error("robots:\n  - name: r\n    x_m: 0\n    y_m: 0\n    odometry:\n      lefft_scale: 1.0\n") ==
        "w.yaml:6:7: unknown key 'lefft_scale' in 'odometry' (expected one of left_scale, right_scale, "
        "track_ratio, random_trans_per_unit, random_rot_per_unit)");
  CHECK(load_error("robot:\n  - {name: r, x_m: 0, y_m: 0}\n") ==
        "w.yaml:1:1: unknown key 'robot' in the world file (expected one of walls, robots, defaults, seed, radio)");
  CHECK(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, pose: 1}\n") ==
        "w.yaml:2:31: unknown key 'pose' in a robot (expected one of name, x_m, y_m, theta_deg, subclass, port, "
        "odometry, sonar, gyro, limits)");
  CHECK(load_error("defaults:\n  sonar: {range_m: 4}\nrobots:\n  - {name: r, x_m: 0, y_m: 0}\n") ==
        "w.yaml:2:11: unknown key 'range_m' in 'sonar' (expected one of max_range_m, noise_sd_m)");
}

TEST_CASE("a missing required key is an error naming the key, at the mapping that lacks it") {
  CHECK(load_error("robots:\n  - name: r\n    y_m: 0\n") == "w.yaml:2:5: missing required key 'x_m' in a robot");
  CHECK(load_error("robots:\n  - {x_m: 0, y_m: 0}\n") == "w.yaml:2:5: missing required key 'name' in a robot");
  CHECK(load_error("walls: []\n") == "w.yaml:1:1: missing required key 'robots' in the world file");
}

TEST_CASE("a wrong type is an error at the value, saying what was expected and what was found") {
  CHECK(load_error("robots:\n  - name: r\n    x_m: north\n    y_m: 0\n") ==
        "w.yaml:3:10: expected a number for 'x_m', got 'north'");
  CHECK(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, odometry: 3}\n") ==
        "w.yaml:2:41: expected a mapping for 'odometry', got '3'");
  CHECK(load_error("walls: [[0, 0, 1]]\nrobots:\n  - {name: r, x_m: 5, y_m: 5}\n") ==
        "w.yaml:1:9: expected a wall [x0, y0, x1, y1] (4 numbers, metres) for 'walls[0]', got a list of 3");
  CHECK(load_error("robots: 5\n") == "w.yaml:1:9: expected 'robots' to be a non-empty list of robots, got '5'");
  CHECK(load_error("robots: []\n") == "w.yaml:1:9: expected 'robots' to be a non-empty list of robots, got a list");
  CHECK(load_error("robots:\n  - 7\n") == "w.yaml:2:5: expected a mapping for each robot, got '7'");
  CHECK(load_error("- robots\n") == "w.yaml:1:1: expected a mapping for the world file, got a list");
  CHECK(load_error("robots:\n  - {name: [r], x_m: 0, y_m: 0}\n") ==
        "w.yaml:2:12: expected a string for 'name', got a list");
  CHECK(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, port: 80.5}\n") ==
        "w.yaml:2:37: expected an integer for 'port', got '80.5'");
  // As in missions and robot models: a quoted "1.5" is a string, not a number.
  CHECK(load_error("robots:\n  - {name: r, x_m: \"1.5\", y_m: 0}\n") ==
        "w.yaml:2:20: expected a number for 'x_m', got the quoted string \"1.5\"");
}

TEST_CASE("the error is the project's located error: file, line, column and detail apart") {
  try {
    (void)parse_world("robots:\n  - name: r\n    x_m: north\n    y_m: 0\n", "w.yaml");
    FAIL("expected an error");
  } catch (const p3at::LocatedError& e) {
    CHECK(dynamic_cast<const WorldFileError*>(&e) != nullptr);
    CHECK(e.file() == "w.yaml");
    CHECK(e.line() == 3);
    CHECK(e.column() == 10);
    CHECK(e.detail() == "expected a number for 'x_m', got 'north'");
  }
}

TEST_CASE("out-of-range and inconsistent values are errors") {
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, subclass: p3dx}\n"), "\"p3at-sh\" or \"p3at\""));
  CHECK(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, port: 70000}\n") ==
        "w.yaml:2:37: 'port' out of range: 70000 (expected 1 <= port <= 65535)");
  CHECK(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, odometry: {left_scale: 0}}\n") ==
        "w.yaml:2:54: 'left_scale' out of range: 0 (expected left_scale > 0)");
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, sonar: {noise_sd_m: -1}}\n"),
                 "(expected noise_sd_m >= 0)"));
  CHECK(load_error("robots:\n  - {name: r, x_m: .nan, y_m: 0}\n") == "w.yaml:2:20: expected a number for 'x_m', got '.nan'");
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: .inf, y_m: 0}\n"), "expected a number for 'x_m', got '.inf'"));
  CHECK(contains(load_error("robots:\n  - {name: 'bad name', x_m: 0, y_m: 0}\n"), "letters, digits"));
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0}\n  - {name: r, x_m: 5, y_m: 0}\n"),
                 "w.yaml:3:5: duplicate robot name 'r'"));
  CHECK(contains(load_error("robots:\n  - {name: a, x_m: 0, y_m: 0, port: 9000}\n  - {name: b, x_m: 5, y_m: 0, port: 9000}\n"),
                 "duplicate port 9000"));
  CHECK(contains(load_error("robots:\n  - {name: a, x_m: 0, y_m: 0}\n  - {name: b, x_m: 0.3, y_m: 0}\n"),
                 "starts overlapping robot 'a'"));
  CHECK(contains(load_error("walls: [[0.2, -1, 0.2, 1]]\nrobots:\n  - {name: a, x_m: 0, y_m: 0}\n"),
                 "starts touching the wall"));
  CHECK(contains(load_error("walls: [[1, 1, 1, 1]]\nrobots:\n  - {name: a, x_m: 0, y_m: 0}\n"), "distinct end points"));
  CHECK(contains(load_error("robots:\n  - {name: a, x_m: 0, y_m: 0, name: b}\n"), "duplicate key 'name'"));
  CHECK(contains(load_error("seed: -3\nrobots:\n  - {name: a, x_m: 0, y_m: 0}\n"), "non-negative integer"));
}

TEST_CASE("the gyro block: opt-in per robot, field-wise overrides, enabled: false, errors") {
  const std::string text = R"(defaults:
  gyro: {bias_degps: 0.2, noise_sd_degps: 0.1}
robots:
  - {name: a, x_m: 0, y_m: 0}
  - {name: b, x_m: 5, y_m: 0, gyro: {bias_degps: -0.3, scale_error: 0.01}}
  - {name: c, x_m: 10, y_m: 0, gyro: {enabled: false}}
)";
  const WorldConfig w = parse_world(text, "w.yaml");
  REQUIRE(w.robots[0].gyro.has_value());
  CHECK(w.robots[0].gyro->bias_degps == doctest::Approx(0.2));
  REQUIRE(w.robots[1].gyro.has_value());
  CHECK(w.robots[1].gyro->bias_degps == doctest::Approx(-0.3));   // overridden
  CHECK(w.robots[1].gyro->noise_sd_degps == doctest::Approx(0.1));  // from defaults
  CHECK(w.robots[1].gyro->scale_error == doctest::Approx(0.01));
  CHECK_FALSE(w.robots[2].gyro.has_value());

  // Only the robot with the block has a gyro; an empty block is a perfect gyro.
  const WorldConfig one = parse_world("robots:\n  - {name: a, x_m: 0, y_m: 0, gyro: {}}\n  - {name: b, x_m: 5, y_m: 0}\n", "w.yaml");
  REQUIRE(one.robots[0].gyro.has_value());
  CHECK(one.robots[0].gyro->bias_degps == 0.0);
  CHECK(one.robots[0].gyro->noise_sd_degps == 0.0);
  CHECK_FALSE(one.robots[1].gyro.has_value());

  const std::string bad_enabled = load_error("robots:\n  - name: r\n    x_m: 0\n    y_m: 0\n    gyro: {enabled: maybe}\n");
  CHECK(contains(bad_enabled, "w.yaml:5:21:"));
  CHECK(contains(bad_enabled, "expected true or false for 'enabled'"));
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, gyro: {noise_sd_degps: -1}}\n"),
                 "(expected noise_sd_degps >= 0)"));
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, gyro: {scale_error: -1}}\n"),
                 "(expected scale_error > -1)"));
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, gyro: {enabled: \"true\"}}\n"),
                 "expected true or false for 'enabled', got the quoted string \"true\""));
  CHECK(contains(load_error("robots:\n  - {name: r, x_m: 0, y_m: 0, gyro: {bias: 1}}\n"), "unknown key 'bias' in 'gyro'"));
}

TEST_CASE("broken YAML, an empty file and a missing file are errors with a position or the path") {
  CHECK(contains(load_error("robots: [\n  - {name: r\n"), "w.yaml:"));
  // The shared reader's form (common/yaml's yaml_document), as for missions and models.
  CHECK(contains(load_error("robots: [\n  - {name: r\n"), ": malformed YAML: "));
  CHECK(contains(load_error(""), "empty world file"));
  // yaml-cpp 0.7 alone would loop forever on a stray ',' at the top level.
  CHECK(load_error(",") == "w.yaml:1:1: malformed YAML: unexpected ','");
  CHECK(contains(load_error("robots: [{name: r, x_m: 0, y_m: 0}]\n---\nrobots: []\n"),
                 "expected a single YAML document, found a second one"));
  try {
    (void)load_world_file("/nonexistent/world.yaml");
    FAIL("expected an error");
  } catch (const WorldFileError& e) {
    CHECK(contains(e.what(), "/nonexistent/world.yaml: cannot open"));
  }
}

TEST_CASE("the example worlds load") {
  const WorldConfig open = load_world_file(std::string(P3AT_SOURCE_DIR) + "/examples/worlds/open.yaml");
  REQUIRE(open.robots.size() == 1);
  CHECK(open.robots[0].name == "robot1");
  CHECK(open.walls.empty());

  const WorldConfig hall = load_world_file(std::string(P3AT_SOURCE_DIR) + "/examples/worlds/two_robots_hallway.yaml");
  REQUIRE(hall.robots.size() == 2);
  CHECK(hall.robots[0].start.x_m == doctest::Approx(5.5));
  CHECK(hall.robots[1].start.x_m == doctest::Approx(6.5));
  CHECK(hall.robots[1].odometry.right_scale == doctest::Approx(1.01));
  CHECK(hall.walls.size() == 4);
  // And the hallway world runs: both robots can drive along it without touching the walls.
  World world(hall, 7);
  for (std::size_t i = 0; i < 2; ++i) {
    world.robot(i).controller().enable_motors(true);
    world.robot(i).controller().command_trans_vel(0.3);
  }
  p3at::sim::test::run_for(world, 3.0);
  CHECK(world.robot(1).true_pose().x_m > 7.0);
  CHECK_FALSE(world.robot(1).left_stall());
}

TEST_CASE("every world file shipped in the tree loads (examples, test data)") {
  // The loader's typing rules are the shared reader's; no shipped world may fall foul of them.
  std::size_t loaded = 0;
  for (const char* folder : {"/examples", "/tests/data"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(P3AT_SOURCE_DIR) + folder)) {
      const std::string path = entry.path().string();
      const bool world = entry.path().filename() == "world.yaml" ||
                         entry.path().parent_path().filename() == "worlds";
      if (!entry.is_regular_file() || !world) continue;
      CAPTURE(path);
      CHECK_FALSE(load_world_file(path).robots.empty());
      ++loaded;
    }
  }
  CHECK(loaded >= 20);
}

TEST_CASE("the default world is one robot1 at the origin") {
  const WorldConfig w = default_world();
  REQUIRE(w.robots.size() == 1);
  CHECK(w.robots[0].name == "robot1");
  CHECK(w.robots[0].subclass == "p3at-sh");
  CHECK(w.walls.empty());
}

TEST_CASE("the radio block: values, defaults, and errors with a position") {
  const WorldConfig w = parse_world(
      "radio:\n  latency_median_ms: 12\n  loss_probability: 0.05\nrobots:\n  - {name: r, x_m: 0, y_m: 0}\n", "w.yaml");
  CHECK(w.radio.latency_median_ms == doctest::Approx(12.0));
  CHECK(w.radio.loss_probability == doctest::Approx(0.05));
  CHECK(w.radio.latency_min_ms == doctest::Approx(RadioParams{}.latency_min_ms));  // default kept

  const std::string typo = load_error("radio:\n  latency_medain_ms: 3\nrobots:\n  - {name: r, x_m: 0, y_m: 0}\n");
  CHECK(contains(typo, "w.yaml:2:3:"));
  CHECK(contains(typo, "unknown key 'latency_medain_ms'"));

  const std::string range = load_error("radio:\n  loss_probability: 1.5\nrobots:\n  - {name: r, x_m: 0, y_m: 0}\n");
  CHECK(contains(range, "w.yaml:"));
  CHECK(contains(range, "loss_probability"));
}
