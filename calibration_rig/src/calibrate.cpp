// vipars calibrate: the robot-models file the verifier reads, from data
// (docs/calibration.md). Three sources of data:
//   --world FILE          fast-time simulated robots through the normal HAL (SimDriveBase),
//                         and notifications over the simulated team link;
//   --hal URL             one robot over ARCOS (p3at_sim or a real Pioneer);
//   --from-log FILE.csv   a log of such runs, e.g. a lab's own.
// Whatever drove the robots, the fit reads only the log: commands, odometry,
// true poses and message times, never a simulator's parameters.
// (The flags: apps/vipars/calibrate_cli.cpp; the run: here.)

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p3at/calibration_rig/calibrate_drive.hpp"
#include "p3at/calibration_rig/calibrate_hal.hpp"
#include "p3at/calibration_rig/calibrate_messages.hpp"
#include "p3at/calibration_rig/calibrate.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/common/vipars_exit.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/sim/p3at_model.hpp"
#include "p3at/sim/sim_drive_base.hpp"
#include "p3at/sim/world.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/verifier/calibration.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::vipars {
namespace {


// The command line that reproduces this file (its `generated_by`).
std::string command_line(const CalibrateOptions& o) {
  std::string c = "vipars calibrate";
  const auto add = [&c](const std::string& flag, const std::string& value) {
    // Quoted for a shell when it holds anything but the plain characters of paths and numbers.
    const bool plain = !value.empty() && value.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                                 "0123456789_-+.,/:=@%") == std::string::npos;
    std::string quoted = "'";
    for (char ch : value) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    c += " " + flag + " " + (plain ? value : quoted + "'");
  };
  if (!o.world_file.empty()) add("--world", o.world_file);
  if (!o.mission_file.empty()) add("--mission", o.mission_file);
  if (!o.robots.empty()) {
    std::string list;
    for (const std::string& r : o.robots) list += (list.empty() ? "" : ",") + r;
    add("--robots", list);
  }
  if (!o.from_log.empty()) {
    add("--from-log", o.from_log);
  } else {
    if (!o.hal_url.empty()) add("--hal", o.hal_url);
    if (!o.truth_csv.empty()) add("--truth-csv", o.truth_csv);
    if (!o.hal_url.empty() && o.plan.speedup != 1.0) add("--speedup", format_general(o.plan.speedup));
    add("--runs", std::to_string(o.plan.runs));
    if (o.mission_file.empty()) add("--speed", format_general(o.plan.speed_mps));
    add("--distance", format_general(o.plan.distance_m));
    add("--spin-deg", format_general(o.plan.spin_deg));
    if (o.mission_file.empty()) add("--spin-rate", format_general(o.plan.spin_rate_degps));
    if (o.hal_url.empty()) {
      add("--messages", std::to_string(o.messages));
      add("--peer-phase", o.peer_phase);
    }
    if (o.seed) add("--seed", std::to_string(*o.seed));
  }
  if (!o.out_file.empty()) add("--out", o.out_file);
  return c;
}

// The plan for one robot: the flags', or with a mission the robot's own.
ManoeuvrePlan plan_for(const std::string& robot, const ManoeuvrePlan& flags, const std::optional<mission::Mission>& m) {
  if (m) {
    for (const mission::RobotSpec& spec : m->robots) {
      if (spec.name == robot) return plan_for_robot(spec, flags);
    }
  }
  return flags;
}

// Each robot in a wall-free world of its own: calibration needs open floor,
// and one robot's runs must not meet another's.
void drive_simulated(const sim::WorldConfig& world, const std::vector<std::string>& robots, const ManoeuvrePlan& flags,
                     const std::optional<mission::Mission>& mission, std::uint64_t seed, verifier::CalibrationLog& log) {
  std::int64_t next_id = 0;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    sim::WorldConfig open;
    open.radio = world.radio;
    for (const sim::RobotConfig& r : world.robots) {
      if (r.name == robots[i]) open.robots.push_back(r);
    }
    sim::World w(open, seed ^ (0x9E3779B97F4A7C15ULL * (i + 1)));
    sim::SimDriveBase base(w, 0);
    // The simulator's ground truth plays the motion-capture system.
    const TruthProbe truth = [&w](bool) -> std::optional<verifier::TruePose> {
      const sim::Pose& p = w.robot(0).true_pose();
      return verifier::TruePose{p.x_m, p.y_m, p.theta_rad};
    };
    drive_manoeuvres(base, robots[i], plan_for(robots[i], flags, mission), truth, next_id, log.manoeuvres);
  }
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  return static_cast<bool>(out);
}

// The models file: a header that says how to regenerate it, write_models()'s
// text, and the walls by reference to the world file (write_models writes
// walls out in full; a reference keeps the map and the world in step).
std::string models_text(const verifier::Models& models, const CalibrateOptions& o) {
  std::string text =
      "# Written by `vipars calibrate` from calibration runs (docs/calibration.md). To regenerate it,\n"
      "# in the folder the command was run in:\n";
  text += "#   " + models.generated_by + "\n";
  text += verifier::write_models(models);
  if (!o.world_file.empty()) {
    const std::filesystem::path base =
        o.out_file.empty() ? std::filesystem::current_path()
                           : std::filesystem::absolute(o.out_file).parent_path();
    const std::string walls_from =
        std::filesystem::absolute(o.world_file).lexically_normal().lexically_relative(base.lexically_normal()).string();
    const std::string marker = "\nenvironment:\n";
    const std::size_t at = text.find(marker);
    // Plain when YAML reads it back as the same string, double-quoted otherwise.
    const bool plain = !walls_from.empty() &&
                       walls_from.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./-") ==
                           std::string::npos;
    std::string value = "\"";
    for (char ch : walls_from) value += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
    value += "\"";
    if (at != std::string::npos) text.insert(at + marker.size(), "  walls_from: " + (plain ? walls_from : value) + "\n");
  }
  return text;
}

}  // namespace

int run_calibrate(CalibrateOptions o) {
  const bool simulated = o.hal_url.empty() && o.from_log.empty();
  if (!o.hal_url.empty() && !o.from_log.empty()) {
    std::fprintf(stderr, "vipars calibrate: --hal and --from-log are alternatives: give one\n");
    return kExitBadInput;
  }
  if (simulated && o.world_file.empty()) {
    std::fprintf(stderr, "vipars calibrate: give --world FILE (simulated robots), --hal URL or --from-log FILE\n");
    return kExitBadInput;
  }
  for (std::size_t i = 0; i < o.robots.size(); ++i) {
    if (std::find(o.robots.begin(), o.robots.begin() + static_cast<std::ptrdiff_t>(i), o.robots[i]) !=
        o.robots.begin() + static_cast<std::ptrdiff_t>(i)) {
      std::fprintf(stderr, "vipars calibrate: --robots names '%s' twice\n", o.robots[i].c_str());
      return kExitBadInput;
    }
  }
  if (!o.hal_url.empty() && o.robots.size() != 1) {
    std::fprintf(stderr, "vipars calibrate: --hal drives one robot: name it with --robots NAME\n");
    return kExitBadInput;
  }
  if (!o.hal_url.empty() && o.truth_csv.empty() && o.log_out.empty()) {
    std::fprintf(stderr,
                 "vipars calibrate: without --truth-csv the runs have no true poses: give --log-out FILE, measure "
                 "the poses and fit with --from-log FILE (docs/calibration.md)\n");
    return kExitBadInput;
  }

  std::optional<mission::Mission> mission;
  if (!o.mission_file.empty()) {
    if (!o.from_log.empty()) {
      std::fprintf(stderr, "vipars calibrate: --mission sets the runs' speeds: it does not apply to --from-log\n");
      return kExitBadInput;
    }
    try {
      mission = mission::load_mission_file(o.mission_file);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vipars calibrate: %s\n", e.what());
      return kExitBadInput;
    }
    if (o.robots.empty() && o.hal_url.empty()) {
      for (const mission::RobotSpec& r : mission->robots) o.robots.push_back(r.name);
    }
    for (const std::string& name : o.robots) {
      const auto named = [&name](const mission::RobotSpec& r) { return r.name == name; };
      if (std::none_of(mission->robots.begin(), mission->robots.end(), named)) {
        std::fprintf(stderr, "vipars calibrate: %s has no robot named '%s'\n", o.mission_file.c_str(), name.c_str());
        return kExitBadInput;
      }
    }
  }

  std::optional<sim::WorldConfig> world;
  if (!o.world_file.empty()) {
    try {
      world = sim::load_world_file(o.world_file);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vipars calibrate: %s\n", e.what());
      return kExitBadInput;
    }
  }

  verifier::CalibrationLog log;
  std::vector<std::string> robots = o.robots;
  try {
    if (!o.from_log.empty()) {
      log = verifier::load_calibration_log(o.from_log);
    } else if (!o.hal_url.empty()) {
      drive_over_arcos(o.hal_url, robots.front(), plan_for(robots.front(), o.plan, mission), o.truth_csv,
                       log.manoeuvres);
    } else {
      if (robots.empty()) {
        for (const sim::RobotConfig& r : world->robots) robots.push_back(r.name);
      }
      for (const std::string& name : robots) {
        const auto has = [&name](const sim::RobotConfig& r) { return r.name == name; };
        if (std::none_of(world->robots.begin(), world->robots.end(), has)) {
          std::fprintf(stderr, "vipars calibrate: %s has no robot named '%s'\n", o.world_file.c_str(), name.c_str());
          return kExitBadInput;
        }
      }
      const std::uint64_t seed = o.seed.value_or(world->seed.value_or(1));
      o.seed = seed;  // written into generated_by: the file says how to make it again
      drive_simulated(*world, robots, o.plan, mission, seed, log);
      MessagePlan messages;
      messages.count = o.messages;
      messages.cycle_s = static_cast<double>(sim::kCycleUs) / 1e6;
      messages.random_phase = o.peer_phase == "random";
      log.messages = measure_messages(world->radio, robots, messages, seed);
    }
  } catch (const verifier::CalibrationLogError& e) {
    std::fprintf(stderr, "vipars calibrate: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vipars calibrate: %s\n", e.what());
    return o.from_log.empty() ? kExitFailed : kExitBadInput;
  }
  // With --from-log, --robots picks robots out of the log.
  if (!o.from_log.empty() && !robots.empty()) {
    std::erase_if(log.manoeuvres, [&](const verifier::Manoeuvre& m) {
      return std::find(robots.begin(), robots.end(), m.robot) == robots.end();
    });
  }

  if (!o.log_out.empty() && !write_text(o.log_out, verifier::write_calibration_log(log))) {
    std::fprintf(stderr, "vipars calibrate: cannot write %s\n", o.log_out.c_str());
    return kExitFailed;
  }
  if (!o.hal_url.empty() && o.truth_csv.empty()) {
    std::fprintf(stderr,
                 "vipars calibrate: wrote %zu manoeuvres to %s without true poses; fill in true_x_m, true_y_m and "
                 "true_theta_rad on each manoeuvre's first and last rows, then run: vipars calibrate --from-log %s\n",
                 log.manoeuvres.size(), o.log_out.c_str(), o.log_out.c_str());
    return kExitOk;
  }

  verifier::CalibrationResult result;
  try {
    result = verifier::calibrate(log);
  } catch (const std::exception& e) {  // CalibrationError: data that cannot give a model
    std::fprintf(stderr, "vipars calibrate: %s\n", e.what());
    return o.from_log.empty() ? kExitFailed : kExitBadInput;
  }
  for (const std::string& name : robots) {
    const bool found = std::any_of(result.robots.begin(), result.robots.end(),
                                   [&](const verifier::RobotCalibration& r) { return r.model.name == name; });
    if (!found) {
      std::fprintf(stderr, "vipars calibrate: no manoeuvres of '%s' in the log\n", name.c_str());
      return kExitBadInput;
    }
  }
  std::fputs(verifier::format_calibration_report(result).c_str(), stderr);

  verifier::Models models = verifier::to_models(result);
  models.generated_by = command_line(o);
  // Read back what is about to be written: the verifier must load it as fitted.
  std::string text;
  try {
    text = models_text(models, o);
    const std::string base =
        o.out_file.empty() ? std::string(".") : std::filesystem::absolute(o.out_file).parent_path().string();
    const verifier::Models again = verifier::parse_models(text, o.out_file.empty() ? "<stdout>" : o.out_file, base);
    if (again.robots.size() != models.robots.size()) throw std::runtime_error("robots lost");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vipars calibrate: the models file does not load back: %s\n", e.what());
    return kExitFailed;
  }
  if (o.out_file.empty()) {
    std::fputs(text.c_str(), stdout);
  } else if (!write_text(o.out_file, text)) {
    std::fprintf(stderr, "vipars calibrate: cannot write %s\n", o.out_file.c_str());
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace p3at::vipars
