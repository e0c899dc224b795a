#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "p3at/common/located_error.hpp"
#include "p3at/common/world_walls.hpp"
#include "p3at/common/yaml_document.hpp"
#include "p3at/sim/p3at_model.hpp"
#include "p3at/sim/world_config.hpp"

namespace p3at::sim {
namespace {

constexpr std::size_t kMaxNameLength = 32;

// The shared YAML readers' errors as this loader's: WorldFileError, "file:line:column: detail".
class WorldSource final : public yaml_reader::Source {
 public:
  using yaml_reader::Source::Source;

 protected:
  [[noreturn]] void raise(int line, int column, std::string detail) const override {
    throw WorldFileError(LocatedError::format(name(), line, column, detail));
  }
};

class Loader {
 public:
  explicit Loader(std::string source) : source_(std::move(source)) {}

  WorldConfig load(const std::string& text) {
    // The one safe reader every YAML input shares (common/yaml): malformed
    // YAML, a second document or yaml-cpp 0.7's endless loop on a stray ','
    // become "file:line:column: malformed YAML: ...".
    const std::string empty = "empty world file: expected a mapping with 'robots' (and optional 'walls')";
    YAML::Node root;
    try {
      root = yaml_document::load_single(text, empty);
    } catch (const yaml_document::Problem& problem) {
      if (problem.detail == empty) throw WorldFileError(source_ + ": " + empty);
      throw WorldFileError(at(problem.mark) + ": " + problem.detail);
    }
    expect_map(root, "the world file");
    check_keys(root, {"walls", "robots", "defaults", "seed", "radio"}, "the world file");

    WorldConfig world;
    if (const YAML::Node seed = root["seed"]; seed.IsDefined()) world.seed = read_seed(seed);
    if (const YAML::Node walls = root["walls"]; walls.IsDefined() && !walls.IsNull()) read_walls(walls, world.walls);

    read_radio(root, world.radio);

    RobotConfig defaults;
    defaults.name.clear();
    if (const YAML::Node d = root["defaults"]; d.IsDefined() && !d.IsNull()) {
      expect_map(d, "'defaults'");
      check_keys(d, {"odometry", "sonar", "gyro", "limits"}, "'defaults'");
      read_models(d, defaults);
    }

    const YAML::Node robots = root["robots"];
    if (!robots.IsDefined()) throw WorldFileError(at(root.Mark()) + ": missing required field 'robots'");
    if (!robots.IsSequence() || robots.size() == 0) {
      throw WorldFileError(at(robots.Mark()) + ": expected 'robots' to be a non-empty list of robots");
    }
    for (const YAML::Node& r : robots) world.robots.push_back(read_robot(r, defaults));
    check_world(world, robots);
    return world;
  }

 private:
  std::string at(const YAML::Mark& mark) const {
    if (mark.is_null()) return source_;
    return source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
  }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& what) const {
    throw WorldFileError(at(node.Mark()) + ": " + what);
  }

  static std::string describe(const YAML::Node& node) {
    switch (node.Type()) {
      case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
      case YAML::NodeType::Sequence: return "a list";
      case YAML::NodeType::Map: return "a mapping";
      case YAML::NodeType::Null: return "nothing";
      case YAML::NodeType::Undefined: return "nothing";
    }
    return "something else";
  }

  void expect_map(const YAML::Node& node, const std::string& what) const {
    if (!node.IsMap()) fail(node, "expected " + what + " to be a mapping (key: value), got " + describe(node));
  }

  void check_keys(const YAML::Node& map, std::initializer_list<std::string_view> allowed,
                  const std::string& what) const {
    std::set<std::string> seen;
    for (const auto& kv : map) {
      const YAML::Node& key = kv.first;
      if (!key.IsScalar()) fail(key, "expected a key name in " + what);
      const std::string& name = key.Scalar();
      bool known = false;
      std::string list;
      for (std::string_view a : allowed) {
        if (a == name) known = true;
        list += (list.empty() ? "" : ", ") + std::string(a);
      }
      if (!known) fail(key, "unknown key '" + name + "' in " + what + " (expected one of: " + list + ")");
      if (!seen.insert(name).second) fail(key, "duplicate key '" + name + "' in " + what);
    }
  }

  double read_number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, "expected a number for '" + key + "', got " + describe(node));
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, "expected a number for '" + key + "', got " + describe(node));
    }
    if (!std::isfinite(value)) fail(node, "expected a finite number for '" + key + "', got " + describe(node));
    return value;
  }

  double read_number(const YAML::Node& node, const std::string& key, double min, bool min_exclusive) const {
    const double value = read_number(node, key);
    if (min_exclusive ? !(value > min) : !(value >= min)) {
      std::ostringstream out;
      out << "expected '" << key << "' " << (min_exclusive ? "> " : ">= ") << min << ", got " << describe(node);
      fail(node, out.str());
    }
    return value;
  }

  bool read_bool(const YAML::Node& node, const std::string& key) const {
    if (node.IsScalar()) {
      const std::string& text = node.Scalar();
      if (text == "true") return true;
      if (text == "false") return false;
    }
    fail(node, "expected true or false for '" + key + "', got " + describe(node));
  }

  std::string read_string(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, "expected a string for '" + key + "', got " + describe(node));
    return node.Scalar();
  }

  std::uint64_t read_seed(const YAML::Node& node) const {
    if (!node.IsScalar()) fail(node, "expected a non-negative integer for 'seed', got " + describe(node));
    const std::string& text = node.Scalar();
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 19) {
      fail(node, "expected a non-negative integer for 'seed' (at most 19 digits), got " + describe(node));
    }
    return std::stoull(text);
  }

  // The one reading of a world's walls (common/yaml's world_walls.hpp), the
  // same as the verifier's `walls_from:` of this file.
  void read_walls(const YAML::Node& walls, std::vector<Segment>& out) const {
    const WorldSource src(source_);
    for (const yaml_reader::WallSegment& w : yaml_reader::read_walls(src, walls, walls.Mark(), "walls")) {
      out.push_back(Segment{{w.x0_m, w.y0_m}, {w.x1_m, w.y1_m}});
    }
  }

  // The optional `radio:` block: the simulated team radio's latency and loss.
  void read_radio(const YAML::Node& root, RadioParams& radio) const {
    section(root, "radio",
            {"latency_min_ms", "latency_median_ms", "latency_sigma", "slow_probability", "slow_median_ms",
             "slow_sigma", "loss_probability"},
            [&](const YAML::Node& n, const std::string& k) {
              if (k == "latency_min_ms") radio.latency_min_ms = read_number(n, k, 0.0, false);
              if (k == "latency_median_ms") radio.latency_median_ms = read_number(n, k, 0.0, true);
              if (k == "latency_sigma") radio.latency_sigma = read_number(n, k, 0.0, false);
              if (k == "slow_probability") radio.slow_probability = read_number(n, k, 0.0, false);
              if (k == "slow_median_ms") radio.slow_median_ms = read_number(n, k, 0.0, true);
              if (k == "slow_sigma") radio.slow_sigma = read_number(n, k, 0.0, false);
              if (k == "loss_probability") radio.loss_probability = read_number(n, k, 0.0, false);
            });
    if (const Status ok = validate_radio_params(radio); !ok) fail(root["radio"], ok.error().message);
  }

  // Reads the optional odometry/sonar/gyro/limits sections of `node` over `robot`.
  void read_models(const YAML::Node& node, RobotConfig& robot) const {
    section(node, "odometry", {"left_scale", "right_scale", "track_ratio", "random_trans_per_unit", "random_rot_per_unit"},
            [&](const YAML::Node& n, const std::string& k) {
              OdometryErrors& o = robot.odometry;
              if (k == "left_scale") o.left_scale = read_number(n, k, 0.0, true);
              if (k == "right_scale") o.right_scale = read_number(n, k, 0.0, true);
              if (k == "track_ratio") o.track_ratio = read_number(n, k, 0.0, true);
              if (k == "random_trans_per_unit") o.random_trans_per_unit = read_number(n, k, 0.0, false);
              if (k == "random_rot_per_unit") o.random_rot_per_unit = read_number(n, k, 0.0, false);
            });
    section(node, "sonar", {"max_range_m", "noise_sd_m"}, [&](const YAML::Node& n, const std::string& k) {
      if (k == "max_range_m") robot.sonar.max_range_m = read_number(n, k, 0.0, true);
      if (k == "noise_sd_m") robot.sonar.noise_sd_m = read_number(n, k, 0.0, false);
    });
    // A `gyro:` block gives the robot a gyro (opt-in: without one the heading
    // comes from the wheels, as before gyros were simulated); its fields
    // override the defaults' field by field; `enabled: false` takes it away.
    if (const YAML::Node g = node["gyro"]; g.IsDefined() && !g.IsNull()) {
      GyroModel gyro = robot.gyro.value_or(GyroModel{});
      bool enabled = true;
      section(node, "gyro", {"enabled", "bias_degps", "drift_degps_per_s", "noise_sd_degps", "scale_error"},
              [&](const YAML::Node& n, const std::string& k) {
                if (k == "enabled") enabled = read_bool(n, k);
                if (k == "bias_degps") gyro.bias_degps = read_number(n, k);
                if (k == "drift_degps_per_s") gyro.drift_degps_per_s = read_number(n, k);
                if (k == "noise_sd_degps") gyro.noise_sd_degps = read_number(n, k, 0.0, false);
                if (k == "scale_error") gyro.scale_error = read_number(n, k, -1.0, true);
              });
      robot.gyro = enabled ? std::optional<GyroModel>(gyro) : std::nullopt;
    }
    section(node, "limits",
            {"max_trans_vel_mps", "max_rot_vel_degps", "trans_accel_mps2", "trans_decel_mps2", "rot_accel_degps2",
             "rot_decel_degps2"},
            [&](const YAML::Node& n, const std::string& k) {
              MotionLimits& l = robot.limits;
              if (k == "max_trans_vel_mps") l.max_trans_vel_mps = read_number(n, k, 0.0, true);
              if (k == "max_rot_vel_degps") l.max_rot_vel_degps = read_number(n, k, 0.0, true);
              if (k == "trans_accel_mps2") l.trans_accel_mps2 = read_number(n, k, 0.0, true);
              if (k == "trans_decel_mps2") l.trans_decel_mps2 = read_number(n, k, 0.0, true);
              if (k == "rot_accel_degps2") l.rot_accel_degps2 = read_number(n, k, 0.0, true);
              if (k == "rot_decel_degps2") l.rot_decel_degps2 = read_number(n, k, 0.0, true);
            });
    check_limits(node, robot.limits);
  }

  void check_limits(const YAML::Node& node, const MotionLimits& l) const {
    // The config packet carries these as u16 mm/s, deg/s, mm/s², deg/s².
    if (l.max_trans_vel_mps > 3.0 || l.max_rot_vel_degps > 360.0 || l.trans_accel_mps2 > 10.0 ||
        l.trans_decel_mps2 > 10.0 || l.rot_accel_degps2 > 1000.0 || l.rot_decel_degps2 > 1000.0) {
      fail(node, "expected 'limits' within a Pioneer's range (velocity <= 3 m/s and 360 deg/s, "
                 "acceleration <= 10 m/s² and 1000 deg/s²)");
    }
  }

  void section(const YAML::Node& parent, const char* name, std::initializer_list<std::string_view> keys,
               const std::function<void(const YAML::Node&, const std::string&)>& read_field) const {
    const YAML::Node node = parent[name];
    if (!node.IsDefined() || node.IsNull()) return;
    expect_map(node, std::string("'") + name + "'");
    check_keys(node, keys, std::string("'") + name + "'");
    for (const auto& kv : node) read_field(kv.second, kv.first.Scalar());
  }

  RobotConfig read_robot(const YAML::Node& node, const RobotConfig& defaults) const {
    expect_map(node, "a robot");
    check_keys(node,
               {"name", "x_m", "y_m", "theta_deg", "subclass", "port", "odometry", "sonar", "gyro", "limits"},
               "a robot");
    RobotConfig robot = defaults;
    const auto required = [&](const char* key) {
      const YAML::Node n = node[key];
      if (!n.IsDefined()) fail(node, std::string("missing required field '") + key + "' in a robot");
      return n;
    };
    robot.name = read_string(required("name"), "name");
    if (robot.name.empty() || robot.name.size() > kMaxNameLength ||
        robot.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
            std::string::npos) {
      fail(node["name"], "expected 'name' of 1-32 letters, digits, '_' or '-', got " + describe(node["name"]));
    }
    robot.start.x_m = read_number(required("x_m"), "x_m");
    robot.start.y_m = read_number(required("y_m"), "y_m");
    if (const YAML::Node t = node["theta_deg"]; t.IsDefined()) {
      robot.start.theta_rad = wrap_angle(read_number(t, "theta_deg") * std::numbers::pi / 180.0);
    }
    if (const YAML::Node s = node["subclass"]; s.IsDefined()) {
      robot.subclass = read_string(s, "subclass");
      if (robot.subclass != "p3at-sh" && robot.subclass != "p3at") {
        fail(s, "expected 'subclass' to be \"p3at-sh\" or \"p3at\", got " + describe(s));
      }
    }
    if (const YAML::Node p = node["port"]; p.IsDefined()) {
      const double port = read_number(p, "port");
      if (port < 1.0 || port > 65535.0 || port != std::floor(port)) {
        fail(p, "expected 'port' to be an integer in 1-65535, got " + describe(p));
      }
      robot.port = static_cast<int>(port);
    }
    read_models(node, robot);
    return robot;
  }

  void check_world(const WorldConfig& world, const YAML::Node& robots) const {
    for (std::size_t i = 0; i < world.robots.size(); ++i) {
      const RobotConfig& r = world.robots[i];
      const YAML::Node node = robots[i];
      const Footprint fp{r.start, kP3atLengthM, kP3atWidthM};
      for (std::size_t j = 0; j < i; ++j) {
        const RobotConfig& other = world.robots[j];
        if (other.name == r.name) fail(node, "duplicate robot name '" + r.name + "'");
        if (r.port >= 0 && other.port == r.port) fail(node, "duplicate port " + std::to_string(r.port));
        if (intersects(fp, Footprint{other.start, kP3atLengthM, kP3atWidthM})) {
          fail(node, "robot '" + r.name + "' starts overlapping robot '" + other.name + "'");
        }
      }
      for (const Segment& w : world.walls) {
        if (intersects(fp, w)) {
          std::ostringstream out;
          out << "robot '" << r.name << "' starts touching the wall [" << w.a.x << ", " << w.a.y << ", " << w.b.x
              << ", " << w.b.y << "]";
          fail(node, out.str());
        }
      }
    }
  }

  std::string source_;
};

}  // namespace

WorldConfig parse_world(const std::string& yaml_text, const std::string& source_name) {
  return Loader(source_name).load(yaml_text);
}

WorldConfig load_world_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw WorldFileError(path + ": cannot open world file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw WorldFileError(path + ": cannot read world file");
  return parse_world(text.str(), path);
}

WorldConfig default_world() {
  WorldConfig world;
  world.robots.push_back(RobotConfig{});
  return world;
}

}  // namespace p3at::sim
