// parse_models(): the robot-models file (docs/robot-models.md) into Models.
// Every key is checked (unknown keys are errors, so a typo never silently
// falls back to a default), every value converted to SI here and only here.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "models/text_file.hpp"
#include "models/units.hpp"
#include "models/yaml_access.hpp"
#include "p3at/common/world_walls.hpp"
#include "p3at/mission/names.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier {
namespace {

using models_detail::MapReader;
using models_detail::Range;
using models_detail::Source;

constexpr std::int64_t kVersion = 1;

// Ranges: wide enough for any real robot and link, narrow enough that no
// later arithmetic (squares, sums of weights) can overflow.
constexpr Range kPositive{0.0, 1e6, true, false};
constexpr Range kScale{0.0, 10.0, true, false};
constexpr Range kSd{0.0, 100.0};
constexpr Range kRelativeSd{0.0, 10.0};
constexpr Range kDrift{-360.0, 360.0};
constexpr Range kTurnMove{-1.0, 1.0};
constexpr Range kCycle{0.0, 10.0, true, false};
constexpr Range kWeight{0.0, 1e6, true, false};
constexpr Range kDelayMs{0.0, 1e7};
constexpr Range kRange{0.0, 1000.0, true, false};

std::string indexed(std::string_view label, std::size_t i) { return std::string(label) + "[" + std::to_string(i) + "]"; }

// The element's own mark, or the list's for a null element.
YAML::Mark element_mark(const YAML::Node& list, const YAML::Node& element) {
  return element.IsNull() ? list.Mark() : element.Mark();
}

Kinematics read_kinematics(const MapReader& parent) {
  Kinematics k;
  if (!parent.has("kinematics")) return k;
  const MapReader m = parent.map_at("kinematics", {"cycle_s", "max_rot_vel_degps", "trans_accel_mps2", "trans_decel_mps2",
                                          "rot_accel_degps2", "rot_decel_degps2", "robot_radius_m", "rot_gain",
                                          "calibrated_speed_mps", "top_speed_mps"});
  using models_detail::degrees_to_radians;
  k.cycle_s = m.number_or("cycle_s", kCycle, k.cycle_s);
  if (m.has("max_rot_vel_degps")) k.max_rot_vel_radps = degrees_to_radians(m.number("max_rot_vel_degps", kPositive));
  k.trans_accel_mps2 = m.number_or("trans_accel_mps2", kPositive, k.trans_accel_mps2);
  k.trans_decel_mps2 = m.number_or("trans_decel_mps2", kPositive, k.trans_decel_mps2);
  if (m.has("rot_accel_degps2")) k.rot_accel_radps2 = degrees_to_radians(m.number("rot_accel_degps2", kPositive));
  if (m.has("rot_decel_degps2")) k.rot_decel_radps2 = degrees_to_radians(m.number("rot_decel_degps2", kPositive));
  k.robot_radius_m = m.number_or("robot_radius_m", kRange, k.robot_radius_m);
  k.rot_gain = m.number_or("rot_gain", kPositive, k.rot_gain);
  // Both optional: a file without them still loads (calibrated speed unknown).
  k.calibrated_speed_mps = m.number_or("calibrated_speed_mps", kPositive, k.calibrated_speed_mps);
  k.top_speed_mps = m.number_or("top_speed_mps", kPositive, k.top_speed_mps);
  return k;
}

MotionError read_motion(const MapReader& parent) {
  MotionError e;
  if (!parent.has("motion")) return e;
  const MapReader m = parent.map_at("motion", {"trans_scale", "rot_scale", "drift_deg_per_m", "trans_sd_per_sqrt_m",
                                      "rot_sd_per_sqrt_rad", "heading_sd_per_sqrt_m", "trans_rel_sd", "rot_rel_sd",
                                      "trans_per_rad_m"});
  using models_detail::sd_to_var;
  e.trans_scale = m.number_or("trans_scale", kScale, e.trans_scale);
  e.rot_scale = m.number_or("rot_scale", kScale, e.rot_scale);
  if (m.has("trans_per_rad_m")) e.trans_per_rad_m = m.number("trans_per_rad_m", kTurnMove);
  if (m.has("drift_deg_per_m")) e.drift_rad_per_m = models_detail::degrees_to_radians(m.number("drift_deg_per_m", kDrift));
  if (m.has("trans_sd_per_sqrt_m")) e.trans_var_per_m = sd_to_var(m.number("trans_sd_per_sqrt_m", kSd));
  if (m.has("rot_sd_per_sqrt_rad")) e.rot_var_per_rad = sd_to_var(m.number("rot_sd_per_sqrt_rad", kSd));
  if (m.has("heading_sd_per_sqrt_m")) e.heading_var_per_m = sd_to_var(m.number("heading_sd_per_sqrt_m", kSd));
  if (m.has("trans_rel_sd")) e.trans_rel_var = sd_to_var(m.number("trans_rel_sd", kRelativeSd));
  if (m.has("rot_rel_sd")) e.rot_rel_var = sd_to_var(m.number("rot_rel_sd", kRelativeSd));
  return e;
}

std::vector<RobotModel> read_robots(const MapReader& root) {
  const Source& src = root.source();
  const YAML::Node list = root.sequence("robots");
  if (list.size() == 0) src.fail(root.value_mark("robots"), "expected at least one robot in 'robots', got an empty list");
  std::vector<RobotModel> robots;
  std::map<std::string, YAML::Mark> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    const MapReader m =
        MapReader::at_path(src, node, element_mark(list, node), indexed("robots", i), {"name", "kinematics", "motion"});
    RobotModel robot;
    robot.name = m.string("name");
    if (!mission::is_valid_name(robot.name)) {  // as the mission names robots
      src.fail(m.value_mark("name"), "invalid robot name '" + models_detail::show(robot.name) +
                                         "' for '" + m.label("name") +
                                         "' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
    }
    const auto [first, inserted] = seen.emplace(robot.name, m.value_mark("name"));
    if (!inserted) {
      src.fail(m.value_mark("name"), "duplicate robot name '" + robot.name + "' (first at " +
                                         models_detail::position(first->second) + ")");
    }
    robot.kinematics = read_kinematics(m);
    robot.motion = read_motion(m);
    robots.push_back(std::move(robot));
  }
  return robots;
}

// A delay mixture: a non-empty list of {weight, mean, sd} in ms, held in s.
Mixture1 read_delay(const MapReader& comm, std::string_view key) {
  const Source& src = comm.source();
  const YAML::Node list = comm.sequence(key);
  const std::string label = comm.label(key);
  if (list.size() == 0) {
    src.fail(comm.value_mark(key), "expected at least one component {weight, mean, sd} in '" + label + "', got an empty list");
  }
  Mixture1 out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    const MapReader m = MapReader::at_path(src, node, element_mark(list, node), indexed(label, i), {"weight", "mean", "sd"});
    const double weight = m.number("weight", kWeight);
    const double mean = models_detail::ms_to_s(m.number("mean", kDelayMs));
    const double var = models_detail::sd_ms_to_var_s(m.number("sd", kDelayMs));
    out.components.push_back(Component1{weight, mean, var});
  }
  out.normalise();
  return out;
}

CommModel read_comm(const MapReader& root) {
  CommModel comm;
  if (!root.has("communication")) return comm;
  const MapReader m = root.map_at("communication", {"delivery_ms", "ack_ms"});
  if (m.has("delivery_ms")) comm.delivery_s = read_delay(m, "delivery_ms");
  if (m.has("ack_ms")) comm.ack_s = read_delay(m, "ack_ms");
  return comm;
}

// A list of walls, each [x0, y0, x1, y1] in metres: the one reading of a
// world's walls (common/yaml's world_walls.hpp), as the simulator reads them.
void read_walls(const Source& src, const YAML::Node& list, const YAML::Mark& mark, const std::string& label,
                std::vector<Wall>& walls) {
  for (const yaml_reader::WallSegment& w : yaml_reader::read_walls(src, list, mark, label)) {
    walls.push_back(Wall{w.x0_m, w.y0_m, w.x1_m, w.y1_m});
  }
}

// The top-level `walls:` of another file (a simulator world): nothing else in
// it is read, so the world's own format may grow without breaking this.
void read_walls_from(const MapReader& env, const std::string& base_dir, std::vector<Wall>& walls) {
  const Source& src = env.source();
  const std::string name = env.string("walls_from");
  const YAML::Mark mark = env.value_mark("walls_from");
  if (name.empty()) src.fail(mark, "expected a file path for '" + env.label("walls_from") + "', got an empty string");
  std::filesystem::path path(name);
  if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
  const std::string shown = models_detail::show(path.string(), 200);
  std::string text;
  std::string why;
  if (!models_detail::read_text_file(path.string(), text, why)) {
    src.fail(mark, "cannot read the walls_from file '" + shown + "': " + why);
  }
  const models_detail::ModelsSource world(path.string());
  const YAML::Node root = models_detail::load_document(world, text, "world file (expected a mapping with a 'walls' list)");
  try {
    if (!root.IsMap()) {
      world.fail(root.Mark(), "expected a mapping at the top level (walls_from reads its 'walls' list), got " +
                                  models_detail::describe(root));
    }
    bool has_robots = false;
    for (auto it = root.begin(); it != root.end(); ++it) {
      if (!it->first.IsScalar()) continue;
      if (it->first.Scalar() == "robots") has_robots = true;
      if (it->first.Scalar() != "walls") continue;
      read_walls(world, it->second, it->second.IsNull() ? it->first.Mark() : it->second.Mark(), "walls", walls);
      return;
    }
    // A simulator world without walls is an open floor (docs/simulator.md);
    // a file with neither key is not a world file at all.
    if (has_robots) return;
    world.fail(root.Mark(), "missing top-level key 'walls' (walls_from reads only that list; a world file "
                            "without walls still has 'robots')");
  } catch (const YAML::Exception& e) {
    world.fail(e.mark, "malformed YAML: " + e.msg);
  }
}

Environment read_environment(const MapReader& root, const std::string& base_dir) {
  Environment env;
  if (!root.has("environment")) return env;
  const MapReader m = root.map_at("environment", {"walls_from", "walls", "sonar_max_range_m"});
  if (m.has("walls_from")) read_walls_from(m, base_dir, env.walls);
  if (m.has("walls")) read_walls(m.source(), m.get("walls"), m.value_mark("walls"), m.label("walls"), env.walls);
  env.sonar_max_range_m = m.number_or("sonar_max_range_m", kRange, env.sonar_max_range_m);
  return env;
}

Budget read_budget(const MapReader& root) {
  Budget b;
  if (!root.has("budget")) return b;
  const MapReader m =
      root.map_at("budget", {"max_components", "max_branches", "noise_sigma_points", "max_events", "max_work_cycles"});
  const auto count = [&m](std::string_view key, std::int64_t hi, std::size_t fallback) {
    return m.has(key) ? static_cast<std::size_t>(m.integer(key, 1, hi)) : fallback;
  };
  b.max_components = count("max_components", 1000, b.max_components);
  b.max_branches = count("max_branches", 1000000, b.max_branches);
  b.noise_sigma_points = count("noise_sigma_points", 1000, b.noise_sigma_points);
  b.max_events = count("max_events", 1000000000, b.max_events);
  b.max_work_cycles = count("max_work_cycles", 1'000'000'000'000, b.max_work_cycles);
  return b;
}

Models read_models(const Source& src, const YAML::Node& node, const std::string& base_dir) {
  const MapReader root =
      MapReader::at_path(src, node, YAML::Mark(), "", {"models", "robots", "communication", "environment", "budget"});
  Models models;
  models.source = src.name();
  const MapReader header = root.map_at("models", {"version", "generated_by"});
  const std::int64_t version = header.integer("version", 0, 1000000);
  if (version != kVersion) {
    src.fail(header.value_mark("version"), "unsupported models version " + std::to_string(version) +
                                               " (expected version: " + std::to_string(kVersion) + ")");
  }
  if (header.has("generated_by")) models.generated_by = header.string("generated_by");
  models.robots = read_robots(root);
  models.comm = read_comm(root);
  models.environment = read_environment(root, base_dir);
  models.budget = read_budget(root);
  return models;
}

}  // namespace

Models parse_models(std::string_view yaml_text, const std::string& source_name, const std::string& base_dir) {
  const models_detail::ModelsSource src(source_name);
  const YAML::Node root =
      models_detail::load_document(src, yaml_text, "models file (expected a mapping with keys models, robots, ...)");
  try {
    return read_models(src, root, base_dir);
  } catch (const YAML::Exception& e) {
    // yaml-cpp should not throw while a loaded tree is walked; if it does, still a located error.
    src.fail(e.mark, "malformed YAML: " + e.msg);
  }
}

}  // namespace p3at::verifier
