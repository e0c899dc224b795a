// The robot-models file (docs/robot-models.md): every key and its unit
// conversion, the defaults, each kind of error at its file:line:column, the
// writer's round trip, walls_from, and the shipped example.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

#include "p3at/verifier/models.hpp"
#include "scratch.hpp"

namespace {

using p3at::verifier::Component1;
using p3at::verifier::Kinematics;
using p3at::verifier::Mixture1;
using p3at::verifier::Models;
using p3at::verifier::ModelsError;
using p3at::verifier::MotionError;
using p3at::verifier::Wall;

constexpr double kDeg = std::numbers::pi / 180.0;
const std::string kExampleDir = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch";

// Every key of the format, none at its default.
constexpr std::string_view kFull = R"(# a comment
models:
  version: 1
  generated_by: "vipars calibrate --runs 12"
robots:
  - name: alpha
    kinematics:
      cycle_s: 0.05
      max_rot_vel_degps: 60
      trans_accel_mps2: 0.5
      trans_decel_mps2: 0.4
      rot_accel_degps2: 90
      rot_decel_degps2: 80
      robot_radius_m: 0.35
      rot_gain: 2.0
    motion:
      trans_scale: 0.95
      rot_scale: 1.02
      drift_deg_per_m: -0.5
      trans_sd_per_sqrt_m: 0.01
      rot_sd_per_sqrt_rad: 0.02
      heading_sd_per_sqrt_m: 0.003
      trans_rel_sd: 0.05
      rot_rel_sd: 0.07
      trans_per_rad_m: -0.004
  - name: bravo
communication:
  delivery_ms: [{weight: 3, mean: 6, sd: 2}, {weight: 1, mean: 150, sd: 80}]
  ack_ms:
    - {weight: 1, mean: 12, sd: 0}
environment:
  walls: [[0, 0, 10, 0], [10, 0, 10, -5.5]]
  sonar_max_range_m: 4.5
budget:
  max_components: 6
  max_branches: 20
  noise_sigma_points: 12
  max_events: 5000
)";

Models parse(std::string_view text) { return p3at::verifier::parse_models(text, "m.yaml", kExampleDir); }

// The error message parsing `text` gives, or "no error".
std::string error_of(std::string_view text, const std::string& base_dir = kExampleDir) {
  try {
    (void)p3at::verifier::parse_models(text, "m.yaml", base_dir);
    return "no error";
  } catch (const ModelsError& e) {
    return e.what();
  }
}

// "line:column" (1-based) of the nth occurrence of `at` in `text`.
std::string loc(std::string_view text, std::string_view at, int nth = 1) {
  std::size_t pos = std::string_view::npos;
  for (int i = 0; i < nth; ++i) pos = text.find(at, pos == std::string_view::npos ? 0 : pos + 1);
  REQUIRE(pos != std::string_view::npos);
  const std::string_view before = text.substr(0, pos);
  const std::size_t line_start = before.rfind('\n');
  const std::size_t column = line_start == std::string_view::npos ? pos : pos - line_start - 1;
  const auto line = std::count(before.begin(), before.end(), '\n');
  return std::to_string(line + 1) + ":" + std::to_string(column + 1);
}

std::string replace_once(std::string_view text, std::string_view from, std::string_view to) {
  std::string out(text);
  const std::size_t pos = out.find(from);
  REQUIRE(pos != std::string::npos);
  out.replace(pos, from.size(), to);
  return out;
}

// kFull with `from` replaced by `to` must fail at `at` in the edited text with `detail`.
void check_edit(std::string_view from, std::string_view to, std::string_view at, const std::string& detail) {
  const std::string text = replace_once(kFull, from, to);
  CHECK(error_of(text) == "m.yaml:" + loc(text, at) + ": " + detail);
}

constexpr std::string_view kMinimal = "models: {version: 1}\nrobots:\n  - name: r\n";

void check_close(double a, double b) { CHECK(a == doctest::Approx(b).epsilon(1e-15)); }

void check_same_mixture(const Mixture1& a, const Mixture1& b) {
  REQUIRE(a.components.size() == b.components.size());
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    check_close(a.components[i].weight, b.components[i].weight);
    check_close(a.components[i].mean, b.components[i].mean);
    check_close(a.components[i].var, b.components[i].var);
  }
}

// Equal up to the last bit or so of each converted value.
void check_same(const Models& a, const Models& b) {
  CHECK(a.generated_by == b.generated_by);
  REQUIRE(a.robots.size() == b.robots.size());
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    const Kinematics& ka = a.robots[i].kinematics;
    const Kinematics& kb = b.robots[i].kinematics;
    const MotionError& ea = a.robots[i].motion;
    const MotionError& eb = b.robots[i].motion;
    CHECK(a.robots[i].name == b.robots[i].name);
    check_close(ka.cycle_s, kb.cycle_s);
    check_close(ka.max_rot_vel_radps, kb.max_rot_vel_radps);
    check_close(ka.trans_accel_mps2, kb.trans_accel_mps2);
    check_close(ka.trans_decel_mps2, kb.trans_decel_mps2);
    check_close(ka.rot_accel_radps2, kb.rot_accel_radps2);
    check_close(ka.rot_decel_radps2, kb.rot_decel_radps2);
    check_close(ka.robot_radius_m, kb.robot_radius_m);
    check_close(ka.rot_gain, kb.rot_gain);
    check_close(ea.trans_scale, eb.trans_scale);
    check_close(ea.rot_scale, eb.rot_scale);
    check_close(ea.drift_rad_per_m, eb.drift_rad_per_m);
    check_close(ea.trans_var_per_m, eb.trans_var_per_m);
    check_close(ea.rot_var_per_rad, eb.rot_var_per_rad);
    check_close(ea.heading_var_per_m, eb.heading_var_per_m);
    check_close(ea.trans_rel_var, eb.trans_rel_var);
    check_close(ea.rot_rel_var, eb.rot_rel_var);
    check_close(ea.trans_per_rad_m, eb.trans_per_rad_m);
  }
  check_same_mixture(a.comm.delivery_s, b.comm.delivery_s);
  check_same_mixture(a.comm.ack_s, b.comm.ack_s);
  CHECK(a.environment == b.environment);
  CHECK(a.budget == b.budget);
}

std::filesystem::path temp_dir() {
  static const std::filesystem::path dir = p3at::test::scratch_dir("models");
  return dir;
}

void write_file(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

}  // namespace

TEST_SUITE("reading") {
  TEST_CASE("every key, converted to SI") {
    const Models m = parse(kFull);
    CHECK(m.source == "m.yaml");
    CHECK(m.generated_by == "vipars calibrate --runs 12");
    REQUIRE(m.robots.size() == 2);
    const Kinematics& k = m.robots[0].kinematics;
    CHECK(m.robots[0].name == "alpha");
    CHECK(k.cycle_s == 0.05);
    CHECK(k.max_rot_vel_radps == doctest::Approx(60 * kDeg).epsilon(1e-15));
    CHECK(k.trans_accel_mps2 == 0.5);
    CHECK(k.trans_decel_mps2 == 0.4);
    CHECK(k.rot_accel_radps2 == doctest::Approx(90 * kDeg).epsilon(1e-15));
    CHECK(k.rot_decel_radps2 == doctest::Approx(80 * kDeg).epsilon(1e-15));
    CHECK(k.robot_radius_m == 0.35);
    CHECK(k.rot_gain == 2.0);
    const MotionError& e = m.robots[0].motion;
    CHECK(e.trans_scale == 0.95);
    CHECK(e.rot_scale == 1.02);
    CHECK(e.drift_rad_per_m == doctest::Approx(-0.5 * kDeg).epsilon(1e-15));
    CHECK(e.trans_var_per_m == doctest::Approx(1e-4).epsilon(1e-15));
    CHECK(e.rot_var_per_rad == doctest::Approx(4e-4).epsilon(1e-15));
    CHECK(e.heading_var_per_m == doctest::Approx(9e-6).epsilon(1e-15));
    CHECK(e.trans_rel_var == doctest::Approx(0.0025).epsilon(1e-15));
    CHECK(e.rot_rel_var == doctest::Approx(0.0049).epsilon(1e-15));
    CHECK(e.trans_per_rad_m == -0.004);
    // bravo has neither block: the defaults.
    CHECK(m.robots[1].kinematics == Kinematics{});
    CHECK(m.robots[1].motion == MotionError{});
    // Weights normalised, ms to s, sd in ms to a variance in s^2.
    REQUIRE(m.comm.delivery_s.components.size() == 2);
    CHECK(m.comm.delivery_s.components[0].weight == 0.75);
    CHECK(m.comm.delivery_s.components[0].mean == doctest::Approx(0.006).epsilon(1e-15));
    CHECK(m.comm.delivery_s.components[0].var == doctest::Approx(4e-6).epsilon(1e-15));
    CHECK(m.comm.delivery_s.components[1].weight == 0.25);
    CHECK(m.comm.delivery_s.components[1].mean == doctest::Approx(0.150).epsilon(1e-15));
    CHECK(m.comm.delivery_s.components[1].var == doctest::Approx(0.0064).epsilon(1e-15));
    CHECK(m.comm.ack_s == Mixture1{{Component1{1.0, 0.012, 0.0}}});
    REQUIRE(m.environment.walls.size() == 2);
    CHECK(m.environment.walls[1] == Wall{10, 0, 10, -5.5});
    CHECK(m.environment.sonar_max_range_m == 4.5);
    CHECK(m.budget.max_components == 6);
    CHECK(m.budget.max_branches == 20);
    CHECK(m.budget.noise_sigma_points == 12);
    CHECK(m.budget.max_events == 5000);
  }
  TEST_CASE("defaults: a perfect robot, an ideal link, no walls, the standard budget") {
    const Models m = parse(kMinimal);
    REQUIRE(m.robots.size() == 1);
    CHECK(m.generated_by.empty());
    CHECK(m.robots[0].kinematics == Kinematics{});
    CHECK(m.robots[0].kinematics.max_rot_vel_radps == 0.75);
    CHECK(m.robots[0].motion == MotionError{});
    CHECK(m.robots[0].motion.trans_scale == 1.0);
    CHECK(m.comm.delivery_s == Mixture1::point(0.0));
    CHECK(m.comm.ack_s == Mixture1::point(0.0));
    CHECK(m.environment.walls.empty());
    CHECK(m.environment.sonar_max_range_m == 5.0);
    CHECK(m.budget == p3at::verifier::Budget{});
    CHECK(m.budget.max_components == 8);
  }
  TEST_CASE("the speeds: a file without them loads (calibrated speed unknown, the P3-AT's top speed); both round-trip") {
    const Models old_file = parse(kMinimal);
    CHECK(old_file.robots[0].kinematics.calibrated_speed_mps == 0.0);  // unknown: verify warns
    CHECK(old_file.robots[0].kinematics.top_speed_mps == 0.6);
    const Models m = parse(std::string(kMinimal) + "    kinematics: {calibrated_speed_mps: 0.35, top_speed_mps: 0.5}\n");
    CHECK(m.robots[0].kinematics.calibrated_speed_mps == 0.35);
    CHECK(m.robots[0].kinematics.top_speed_mps == 0.5);
    const Models again = parse(p3at::verifier::write_models(m));
    CHECK(again.robots[0].kinematics == m.robots[0].kinematics);
    // An unknown calibrated speed stays unknown through the writer (not written as 0).
    CHECK(p3at::verifier::write_models(old_file).find("calibrated_speed_mps") == std::string::npos);
  }
  TEST_CASE("find_robot by name") {
    const Models m = parse(kFull);
    REQUIRE(m.find_robot("bravo") != nullptr);
    CHECK(m.find_robot("bravo") == &m.robots[1]);
    CHECK(m.find_robot("charlie") == nullptr);
  }
}

TEST_SUITE("walls_from") {
  TEST_CASE("reads the six walls of the Bounding Overwatch world, then the file's own") {
    const Models m = parse(std::string(kMinimal) + "environment:\n  walls_from: world.yaml\n  walls: [[1, 2, 3, 4]]\n");
    REQUIRE(m.environment.walls.size() == 7);
    CHECK(m.environment.walls[0] == Wall{3.0, 2.5, 24.0, 2.5});
    CHECK(m.environment.walls[5] == Wall{24.0, 2.5, 24.0, 20.5});
    CHECK(m.environment.walls[6] == Wall{1, 2, 3, 4});
  }
  TEST_CASE("an absolute path ignores the base folder") {
    const std::string text = std::string(kMinimal) + "environment: {walls_from: '" + kExampleDir + "/world.yaml'}\n";
    CHECK(p3at::verifier::parse_models(text, "m.yaml", "/nonexistent").environment.walls.size() == 6);
  }
  TEST_CASE("a missing file: the error is at the key's value and names the resolved path") {
    const std::string text = std::string(kMinimal) + "environment:\n  walls_from: no_such_world.yaml\n";
    CHECK(error_of(text) == "m.yaml:" + loc(text, "no_such_world") + ": cannot read the walls_from file '" +
                                kExampleDir + "/no_such_world.yaml': no such file");
    const std::string dir = std::string(kMinimal) + "environment:\n  walls_from: .\n";
    CHECK(error_of(dir) == "m.yaml:" + loc(dir, ".\n") + ": cannot read the walls_from file '" + kExampleDir +
                               "/.': it is a directory");
  }
  TEST_CASE("problems inside the world file are located in the world file") {
    const std::filesystem::path dir = temp_dir();
    const std::string text = std::string(kMinimal) + "environment:\n  walls_from: world_under_test.yaml\n";
    const std::string world = (dir / "world_under_test.yaml").string();

    write_file(world, "seed: 1\nrobots: []\n");  // a world without walls: an open floor, as in the simulator
    CHECK(p3at::verifier::parse_models(text, "m.yaml", dir.string()).environment.walls.empty());
    write_file(world, "seed: 1\nmission: {}\n");  // not a world file
    CHECK(error_of(text, dir.string()) == world +
                                              ":1:1: missing top-level key 'walls' (walls_from reads only that list; a "
                                              "world file without walls still has 'robots')");
    write_file(world, "seed: 1\nwalls:\n  - [0, 0, 1]\n");
    CHECK(error_of(text, dir.string()) ==
          world + ":3:5: expected a wall [x0, y0, x1, y1] (4 numbers, metres) for 'walls[0]', got a list of 3");
    write_file(world, "walls: [[0, 0, 1, x]]\n");
    CHECK(error_of(text, dir.string()) == world + ":1:19: expected a number for 'walls[0][3]', got 'x'");
    write_file(world, "walls: [[0, 0, 1, 1]\n");
    CHECK(error_of(text, dir.string()).starts_with(world + ":2:1: malformed YAML: "));
    // Other keys, however unlike a models file, are none of its business.
    write_file(world, "anything: {goes: [here]}\nwalls: [[0, 0, 1, 1]]\n");
    CHECK(p3at::verifier::parse_models(text, "m.yaml", dir.string()).environment.walls == std::vector<Wall>{{0, 0, 1, 1}});
    std::filesystem::remove(world);
  }
}

TEST_SUITE("errors name file:line:column and what was expected") {
  TEST_CASE("the fixture itself is valid") { CHECK(error_of(kFull) == "no error"); }
  TEST_CASE("a wrong type") {
    check_edit("cycle_s: 0.05", "cycle_s: fast", "fast",
               "expected a number for 'robots[0].kinematics.cycle_s', got 'fast'");
    check_edit("cycle_s: 0.05", "cycle_s: '0.05'", "'0.05'",
               "expected a number for 'robots[0].kinematics.cycle_s', got the quoted string \"0.05\"");
    check_edit("  - name: bravo", "  - name: bravo\n    motion: 3", "3\ncommunication",
               "expected a mapping for 'robots[1].motion', got '3'");
    check_edit("max_events: 5000", "max_events: 50.5", "50.5", "expected an integer for 'budget.max_events', got '50.5'");
    check_edit("  max_events: 5000", "  max_events: 5000\n  max_branches: 3", "max_branches: 3",
               "duplicate key 'max_branches' in budget (first at 36:3)");
  }
  TEST_CASE("an unknown key: typos never fall back to defaults") {
    check_edit("      trans_scale: 0.95", "      trans_sclae: 0.95", "trans_sclae",
               "unknown key 'trans_sclae' in robots[0].motion (expected one of trans_scale, rot_scale, "
               "drift_deg_per_m, trans_sd_per_sqrt_m, rot_sd_per_sqrt_rad, heading_sd_per_sqrt_m, trans_rel_sd, "
               "rot_rel_sd, trans_per_rad_m)");
    check_edit("budget:", "budgets:", "budgets",
               "unknown key 'budgets' at the top level (expected one of models, robots, communication, environment, "
               "budget)");
    check_edit("{weight: 1, mean: 12, sd: 0}", "{weight: 1, mean: 12, sdev: 0}", "sdev",
               "unknown key 'sdev' in communication.ack_ms[0] (expected one of weight, mean, sd)");
  }
  TEST_CASE("out of range: a negative sd, a zero weight, a zero scale, version 2") {
    check_edit("trans_sd_per_sqrt_m: 0.01", "trans_sd_per_sqrt_m: -0.01", "-0.01",
               "'robots[0].motion.trans_sd_per_sqrt_m' out of range: -0.01 (expected 0 <= trans_sd_per_sqrt_m <= 100)");
    check_edit("mean: 150, sd: 80", "mean: 150, sd: -80", "-80",
               "'communication.delivery_ms[1].sd' out of range: -80 (expected 0 <= sd <= 1e+07)");
    check_edit("{weight: 3,", "{weight: 0,", "0,",
               "'communication.delivery_ms[0].weight' out of range: 0 (expected 0 < weight <= 1e+06)");
    check_edit("rot_scale: 1.02", "rot_scale: 0", "0\n      drift",
               "'robots[0].motion.rot_scale' out of range: 0 (expected 0 < rot_scale <= 10)");
    check_edit("version: 1", "version: 2", "2\n  generated_by", "unsupported models version 2 (expected version: 1)");
    check_edit("max_components: 6", "max_components: 0", "0\n  max_branches",
               "'budget.max_components' out of range: 0 (expected 1 <= max_components <= 1000)");
  }
  TEST_CASE("missing or empty required parts") {
    CHECK(error_of("models: {version: 1}\n") == "m.yaml:1:1: missing required key 'robots' at the top level");
    CHECK(error_of("robots: [{name: a}]\n") == "m.yaml:1:1: missing required key 'models' at the top level");
    CHECK(error_of("models: {generated_by: x}\nrobots: [{name: a}]\n") ==
          "m.yaml:1:9: missing required key 'version' in models");
    CHECK(error_of("models: {version: 1}\nrobots: []\n") ==
          "m.yaml:2:9: expected at least one robot in 'robots', got an empty list");
    CHECK(error_of("models: {version: 1}\nrobots:\n") == "m.yaml:2:1: expected a list for 'robots', got null");
    CHECK(error_of("models: {version: 1}\nrobots: [{kinematics: {}}]\n") ==
          "m.yaml:2:10: missing required key 'name' in robots[0]");
    check_edit("  ack_ms:\n    - {weight: 1, mean: 12, sd: 0}", "  ack_ms: []", "[]",
               "expected at least one component {weight, mean, sd} in 'communication.ack_ms', got an empty list");
  }
  TEST_CASE("robot names: unique, and valid as mission names") {
    check_edit("name: bravo", "name: alpha", "alpha\ncommunication", "duplicate robot name 'alpha' (first at 6:11)");
    check_edit("name: bravo", "name: 2nd", "2nd",
               "invalid robot name '2nd' for 'robots[1].name' (expected 1 to 64 letters, digits or '_', not starting "
               "with a digit)");
  }
  TEST_CASE("walls: four numbers each") {
    check_edit("[10, 0, 10, -5.5]", "[10, 0, 10]", "[10, 0, 10]",
               "expected a wall [x0, y0, x1, y1] (4 numbers, metres) for 'environment.walls[1]', got a list of 3");
    check_edit("[10, 0, 10, -5.5]", "[10, 0, 10, .nan]", ".nan",
               "expected a number for 'environment.walls[1][3]', got '.nan'");
  }
  TEST_CASE("malformed YAML") {
    // A lone ',' would make yaml-cpp 0.7 loop forever.
    CHECK(error_of(",") == "m.yaml:1:1: malformed YAML: unexpected ','");
    CHECK(error_of("models: {version: 1}\n,\n") == "m.yaml:2:1: malformed YAML: end of map not found");
    check_edit("[[0, 0, 10, 0], [10, 0, 10, -5.5]]", "[[0, 0, 10, 0], [10, 0, 10, -5.5]", "sonar",
               "malformed YAML: end of sequence flow not found");
    CHECK(error_of("") == "m.yaml:1:1: empty models file (expected a mapping with keys models, robots, ...)");
    CHECK(error_of("- a\n") == "m.yaml:1:1: expected a mapping at the top level, got a list");
    CHECK(error_of(std::string(kMinimal) + "---\nmodels: {version: 1}\n") ==
          "m.yaml:5:1: expected a single YAML document, found a second one");
  }
  TEST_CASE("the structured error carries the parts of the message") {
    try {
      (void)parse("models: {version: 1}\nrobots: [{name: a, speed: 3}]\n");
      FAIL("no error");
    } catch (const ModelsError& e) {
      CHECK(e.file() == "m.yaml");
      CHECK(e.line() == 2);
      CHECK(e.column() == 20);
      CHECK(e.detail() == "unknown key 'speed' in robots[0] (expected one of name, kinematics, motion)");
    }
  }
}

TEST_SUITE("files") {
  TEST_CASE("load_models_file resolves walls_from next to the models file") {
    const std::filesystem::path dir = temp_dir();
    write_file(dir / "world_for_models.yaml", "walls: [[0, 0, 2, 0], [2, 0, 2, 2]]\n");
    write_file(dir / "models_under_test.yaml", std::string(kMinimal) + "environment: {walls_from: world_for_models.yaml}\n");
    const Models m = p3at::verifier::load_models_file((dir / "models_under_test.yaml").string());
    CHECK(m.source == (dir / "models_under_test.yaml").string());
    CHECK(m.environment.walls.size() == 2);
    std::filesystem::remove(dir / "world_for_models.yaml");
    std::filesystem::remove(dir / "models_under_test.yaml");
  }
  TEST_CASE("a file that cannot be read") {
    CHECK_THROWS_WITH_AS(p3at::verifier::load_models_file("/nonexistent/models.yaml"),
                         "/nonexistent/models.yaml: cannot read models file: no such file", ModelsError);
    CHECK_THROWS_WITH_AS(p3at::verifier::load_models_file(kExampleDir),
                         (kExampleDir + ": cannot read models file: it is a directory").c_str(), ModelsError);
  }
  TEST_CASE("the Bounding Overwatch example's models: written by vipars calibrate, with the scales the world implies") {
    const Models m = p3at::verifier::load_models_file(kExampleDir + "/models.yaml");
    CHECK(m.generated_by.rfind("vipars calibrate --world examples/bounding_overwatch/world.yaml", 0) == 0);
    REQUIRE(m.robots.size() == 2);
    const auto* r1 = m.find_robot("robot1");
    const auto* r2 = m.find_robot("robot2");
    REQUIRE(r1 != nullptr);
    REQUIRE(r2 != nullptr);
    // robot1's encoders over-report distance by 10 %; robot2's effective track is 11 % wide.
    CHECK(r1->motion.trans_scale == doctest::Approx(1.0 / 1.1).epsilon(0.002));
    CHECK(r1->motion.rot_scale == doctest::Approx(1.0).epsilon(0.002));
    CHECK(r2->motion.trans_scale == doctest::Approx(1.0).epsilon(0.002));
    CHECK(r2->motion.rot_scale == doctest::Approx(1.0 / 1.11).epsilon(0.002));
    CHECK(r1->motion.rot_rel_var > 0.0);
    CHECK(r2->motion.trans_rel_var > 0.0);
    // MessageSent waits for the acknowledgement and the recipient's next cycle.
    CHECK(m.comm.ack_s.mean() > 0.1);
    CHECK(m.comm.delivery_s.mean() > 0.0);
    CHECK(m.environment.walls.size() == 6);
    CHECK(m.environment.sonar_max_range_m == 5.0);
  }
}

TEST_SUITE("writing") {
  TEST_CASE("a full file round-trips, and writing is a fixed point") {
    const Models m = parse(kFull);
    const std::string text = p3at::verifier::write_models(m);
    const Models again = parse(text);
    check_same(again, m);
    CHECK(p3at::verifier::write_models(again) == text);
    CHECK(text.starts_with("# Robot models for the VIPARS verifier"));
  }
  TEST_CASE("values as calibration computes them come back to the last bit where a decimal allows it") {
    Models m;
    m.generated_by = "vipars calibrate \"runs/*.log\"\tback\\slash";
    p3at::verifier::RobotModel r;
    r.name = "null";  // a name YAML would read as null unless quoted
    r.kinematics.max_rot_vel_radps = 0.7123456789;
    r.kinematics.rot_accel_radps2 = 1.0 / 3.0;
    r.motion.drift_rad_per_m = -0.00123456789;
    r.motion.trans_var_per_m = 1.2345e-5;
    r.motion.rot_var_per_rad = 0.1;
    r.motion.trans_scale = 0.9090909090909091;
    r.motion.rot_rel_var = 0.0004;
    r.motion.trans_per_rad_m = 0.0091452923;
    m.robots.push_back(r);
    m.comm.delivery_s = Mixture1{{Component1{0.6, 0.0071234, 1.1e-5}, Component1{0.4, 0.2, 0.0}}};
    m.comm.ack_s = Mixture1::point(0.013);
    m.environment.walls = {Wall{0.1, 0.2, 0.3, 1e-9}};
    m.budget.max_events = 123456;
    const Models again = parse(p3at::verifier::write_models(m));
    check_same(again, m);
    CHECK(again.robots[0].name == "null");
    // Degrees and milliseconds have an exact decimal for these values.
    CHECK(again.robots[0].kinematics.max_rot_vel_radps == m.robots[0].kinematics.max_rot_vel_radps);
    CHECK(again.robots[0].kinematics.rot_accel_radps2 == m.robots[0].kinematics.rot_accel_radps2);
    CHECK(again.robots[0].motion.drift_rad_per_m == m.robots[0].motion.drift_rad_per_m);
    CHECK(again.comm.delivery_s.components[0].mean == 0.0071234);
    CHECK(again.comm.ack_s == m.comm.ack_s);
    CHECK(again.robots[0].motion.trans_scale == m.robots[0].motion.trans_scale);
  }
  TEST_CASE("an empty delay mixture is left out, and loads as the default") {
    Models m = parse(kMinimal);
    m.comm.ack_s = Mixture1{};
    const std::string text = p3at::verifier::write_models(m);
    CHECK(text.find("ack_ms") == std::string::npos);
    CHECK(parse(text).comm.ack_s == Mixture1::point(0.0));
  }
  TEST_CASE("a value that is not finite cannot be written") {
    Models m = parse(kMinimal);
    m.robots[0].motion.trans_scale = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(p3at::verifier::write_models(m), std::invalid_argument);
  }
  TEST_CASE("the example's models round-trip") {
    const Models m = p3at::verifier::load_models_file(kExampleDir + "/models.yaml");
    const Models again = parse(p3at::verifier::write_models(m));
    check_same(again, m);
  }
}
