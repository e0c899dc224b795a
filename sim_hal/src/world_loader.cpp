// The world file (docs/simulator.md), read with the project's one YAML
// vocabulary (common/yaml): the safe document reader, the mapping reader with
// its fixed keys, typed and ranged getters, and the one reader of walls. Every
// error is a WorldFileError (a LocatedError): "file:line:column: detail".

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/common/world_walls.hpp"
#include "p3at/common/yaml_document.hpp"
#include "p3at/common/yaml_map.hpp"
#include "p3at/common/yaml_reader.hpp"
#include "p3at/sim/p3at_model.hpp"
#include "p3at/sim/world_config.hpp"

namespace p3at::sim {
namespace {

using yaml_reader::MapReader;
using yaml_reader::Range;
using WorldSource = yaml_reader::SourceOf<WorldFileError>;

constexpr std::size_t kMaxNameLength = 32;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Range kAnyNumber{-kInf, kInf};
constexpr Range kPositive{0.0, kInf, true, false};
constexpr Range kNonNegative{0.0, kInf};
// A gyro's scale error: the measured rate is (1 + e) times the true one, so e > -1.
constexpr Range kScaleError{-1.0, kInf, true, false};

const std::vector<std::string> kTopKeys{"walls", "robots", "defaults", "seed", "radio"};
const std::vector<std::string> kDefaultsKeys{"odometry", "sonar", "gyro", "limits"};
const std::vector<std::string> kRobotKeys{"name", "x_m",      "y_m",   "theta_deg", "subclass",
                                          "port", "odometry", "sonar", "gyro",      "limits"};
const std::vector<std::string> kOdometryKeys{"left_scale", "right_scale", "track_ratio", "random_trans_per_unit",
                                             "random_rot_per_unit"};
const std::vector<std::string> kSonarKeys{"max_range_m", "noise_sd_m"};
const std::vector<std::string> kGyroKeys{"enabled", "bias_degps", "drift_degps_per_s", "noise_sd_degps",
                                         "scale_error"};
const std::vector<std::string> kLimitsKeys{"max_trans_vel_mps", "max_rot_vel_degps", "trans_accel_mps2",
                                           "trans_decel_mps2",  "rot_accel_degps2",  "rot_decel_degps2"};
const std::vector<std::string> kRadioKeys{"latency_min_ms", "latency_median_ms", "latency_sigma", "slow_probability",
                                          "slow_median_ms", "slow_sigma",        "loss_probability"};

// The optional block `key` of `parent` ("odometry", ...), its keys checked;
// none if absent or empty (`key:` with nothing after it).
std::optional<MapReader> optional_block(const MapReader& parent, std::string_view key,
                                        const std::vector<std::string>& allowed) {
  if (!parent.has(key) || parent.get(key).IsNull()) return std::nullopt;
  return parent.map(key, "in '" + std::string(key) + "'", allowed);
}

// `seed:` is a std::uint64_t (the simulator's seed), so up to 19 digits; read
// here rather than by MapReader::integer, whose range is std::int64_t's.
std::uint64_t read_seed(const MapReader& top) {
  const YAML::Node node = top.get("seed");
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  if (!node.IsScalar() || text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
      text.size() > 19) {
    top.source().fail(top.value_mark("seed"), "expected a non-negative integer for 'seed' (at most 19 digits), got " +
                                                  yaml_reader::describe(node));
  }
  return std::stoull(text);
}

// The optional `radio:` block: the simulated team radio's latency and loss.
void read_radio(const MapReader& top, RadioParams& radio) {
  if (const auto r = optional_block(top, "radio", kRadioKeys)) {
    radio.latency_min_ms = r->number_or("latency_min_ms", kNonNegative, radio.latency_min_ms);
    radio.latency_median_ms = r->number_or("latency_median_ms", kPositive, radio.latency_median_ms);
    radio.latency_sigma = r->number_or("latency_sigma", kNonNegative, radio.latency_sigma);
    radio.slow_probability = r->number_or("slow_probability", kNonNegative, radio.slow_probability);
    radio.slow_median_ms = r->number_or("slow_median_ms", kPositive, radio.slow_median_ms);
    radio.slow_sigma = r->number_or("slow_sigma", kNonNegative, radio.slow_sigma);
    radio.loss_probability = r->number_or("loss_probability", kNonNegative, radio.loss_probability);
  }
  if (const Status ok = validate_radio_params(radio); !ok) {
    top.source().fail(top.has("radio") ? top.value_mark("radio") : top.mark(), ok.error().message);
  }
}

void check_limits(const MapReader& node, const MotionLimits& l) {
  // The config packet carries these as u16 mm/s, deg/s, mm/s², deg/s².
  if (l.max_trans_vel_mps > 3.0 || l.max_rot_vel_degps > 360.0 || l.trans_accel_mps2 > 10.0 ||
      l.trans_decel_mps2 > 10.0 || l.rot_accel_degps2 > 1000.0 || l.rot_decel_degps2 > 1000.0) {
    node.source().fail(node.mark(), "expected 'limits' within a Pioneer's range (velocity <= 3 m/s and 360 deg/s, "
                                    "acceleration <= 10 m/s² and 1000 deg/s²)");
  }
}

// Reads the optional odometry/sonar/gyro/limits blocks of `node` (a robot or
// `defaults:`) over `robot`, field by field.
void read_models(const MapReader& node, RobotConfig& robot) {
  if (const auto o = optional_block(node, "odometry", kOdometryKeys)) {
    OdometryErrors& e = robot.odometry;
    e.left_scale = o->number_or("left_scale", kPositive, e.left_scale);
    e.right_scale = o->number_or("right_scale", kPositive, e.right_scale);
    e.track_ratio = o->number_or("track_ratio", kPositive, e.track_ratio);
    e.random_trans_per_unit = o->number_or("random_trans_per_unit", kNonNegative, e.random_trans_per_unit);
    e.random_rot_per_unit = o->number_or("random_rot_per_unit", kNonNegative, e.random_rot_per_unit);
  }
  if (const auto s = optional_block(node, "sonar", kSonarKeys)) {
    robot.sonar.max_range_m = s->number_or("max_range_m", kPositive, robot.sonar.max_range_m);
    robot.sonar.noise_sd_m = s->number_or("noise_sd_m", kNonNegative, robot.sonar.noise_sd_m);
  }
  // A `gyro:` block gives the robot a gyro (opt-in: without one the heading
  // comes from the wheels, as before gyros were simulated); its fields
  // override the defaults' field by field; `enabled: false` takes it away.
  if (const auto g = optional_block(node, "gyro", kGyroKeys)) {
    GyroModel gyro = robot.gyro.value_or(GyroModel{});
    const bool enabled = g->has("enabled") ? g->boolean("enabled") : true;
    gyro.bias_degps = g->number_or("bias_degps", kAnyNumber, gyro.bias_degps);
    gyro.drift_degps_per_s = g->number_or("drift_degps_per_s", kAnyNumber, gyro.drift_degps_per_s);
    gyro.noise_sd_degps = g->number_or("noise_sd_degps", kNonNegative, gyro.noise_sd_degps);
    gyro.scale_error = g->number_or("scale_error", kScaleError, gyro.scale_error);
    robot.gyro = enabled ? std::optional<GyroModel>(gyro) : std::nullopt;
  }
  if (const auto m = optional_block(node, "limits", kLimitsKeys)) {
    MotionLimits& l = robot.limits;
    l.max_trans_vel_mps = m->number_or("max_trans_vel_mps", kPositive, l.max_trans_vel_mps);
    l.trans_accel_mps2 = m->number_or("trans_accel_mps2", kPositive, l.trans_accel_mps2);
    l.trans_decel_mps2 = m->number_or("trans_decel_mps2", kPositive, l.trans_decel_mps2);
    l.max_rot_vel_degps = m->number_or("max_rot_vel_degps", kPositive, l.max_rot_vel_degps);
    l.rot_accel_degps2 = m->number_or("rot_accel_degps2", kPositive, l.rot_accel_degps2);
    l.rot_decel_degps2 = m->number_or("rot_decel_degps2", kPositive, l.rot_decel_degps2);
  }
  check_limits(node, robot.limits);
}

RobotConfig read_robot(const WorldSource& src, const YAML::Node& node, const YAML::Mark& list_mark,
                       const RobotConfig& defaults) {
  const MapReader map(src, node, list_mark, "for each robot", "in a robot", "key", kRobotKeys);
  RobotConfig robot = defaults;
  robot.name = map.string("name");
  if (robot.name.empty() || robot.name.size() > kMaxNameLength ||
      robot.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
          std::string::npos) {
    src.fail(map.value_mark("name"),
             "expected 'name' of 1-32 letters, digits, '_' or '-', got " + yaml_reader::describe(map.get("name")));
  }
  robot.start.x_m = map.number("x_m", kAnyNumber);
  robot.start.y_m = map.number("y_m", kAnyNumber);
  if (map.has("theta_deg")) {
    robot.start.theta_rad = wrap_angle(map.number("theta_deg", kAnyNumber) * std::numbers::pi / 180.0);
  }
  if (map.has("subclass")) {
    robot.subclass = map.string("subclass");
    if (robot.subclass != "p3at-sh" && robot.subclass != "p3at") {
      src.fail(map.value_mark("subclass"), "expected 'subclass' to be \"p3at-sh\" or \"p3at\", got " +
                                               yaml_reader::describe(map.get("subclass")));
    }
  }
  if (map.has("port")) robot.port = static_cast<int>(map.integer("port", 1, 65535));
  read_models(map, robot);
  return robot;
}

void check_world(const WorldSource& src, const WorldConfig& world, const YAML::Node& robots) {
  for (std::size_t i = 0; i < world.robots.size(); ++i) {
    const RobotConfig& r = world.robots[i];
    const YAML::Mark at = robots[i].Mark();
    const Footprint fp{r.start, kP3atLengthM, kP3atWidthM};
    for (std::size_t j = 0; j < i; ++j) {
      const RobotConfig& other = world.robots[j];
      if (other.name == r.name) src.fail(at, "duplicate robot name '" + r.name + "'");
      if (r.port >= 0 && other.port == r.port) src.fail(at, "duplicate port " + std::to_string(r.port));
      if (intersects(fp, Footprint{other.start, kP3atLengthM, kP3atWidthM})) {
        src.fail(at, "robot '" + r.name + "' starts overlapping robot '" + other.name + "'");
      }
    }
    for (const Segment& w : world.walls) {
      if (intersects(fp, w)) {
        src.fail(at, "robot '" + r.name + "' starts touching the wall [" + format_general(w.a.x) + ", " +
                         format_general(w.a.y) + ", " + format_general(w.b.x) + ", " + format_general(w.b.y) + "]");
      }
    }
  }
}

WorldConfig load(const WorldSource& src, const std::string& text) {
  // The one safe reader every YAML input shares (common/yaml): malformed
  // YAML, a second document or yaml-cpp 0.7's endless loop on a stray ','
  // become "file:line:column: malformed YAML: ...".
  YAML::Node root;
  try {
    root = yaml_document::load_single(text,
                                      "empty world file: expected a mapping with 'robots' (and optional 'walls')");
  } catch (const yaml_document::Problem& problem) {
    src.fail(problem.mark, problem.detail);
  }
  const MapReader top(src, root, root.Mark(), "for the world file", "in the world file", "key", kTopKeys);

  WorldConfig world;
  if (top.has("seed")) world.seed = read_seed(top);
  // The one reading of a world's walls (common/yaml's world_walls.hpp), the
  // same as the verifier's `walls_from:` of this file.
  if (top.has("walls") && !top.get("walls").IsNull()) {
    for (const yaml_reader::WallSegment& w :
         yaml_reader::read_walls(src, top.get("walls"), top.value_mark("walls"), "walls")) {
      world.walls.push_back(Segment{{w.x0_m, w.y0_m}, {w.x1_m, w.y1_m}});
    }
  }
  read_radio(top, world.radio);

  RobotConfig defaults;
  defaults.name.clear();
  if (const auto d = optional_block(top, "defaults", kDefaultsKeys)) read_models(*d, defaults);

  const YAML::Node robots = top.get("robots");
  if (!robots.IsSequence() || robots.size() == 0) {
    src.fail(top.value_mark("robots"),
             "expected 'robots' to be a non-empty list of robots, got " + yaml_reader::describe(robots));
  }
  for (const YAML::Node& r : robots) world.robots.push_back(read_robot(src, r, top.value_mark("robots"), defaults));
  check_world(src, world, robots);
  return world;
}

}  // namespace

WorldConfig parse_world(const std::string& yaml_text, const std::string& source_name) {
  const WorldSource src(source_name);
  return load(src, yaml_text);
}

WorldConfig load_world_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw WorldFileError(path, 0, 0, "cannot open world file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw WorldFileError(path, 0, 0, "cannot read world file");
  return parse_world(text.str(), path);
}

WorldConfig default_world() {
  WorldConfig world;
  world.robots.push_back(RobotConfig{});
  return world;
}

}  // namespace p3at::sim
