// calibrate_from_world(): the calibration rig (p3at/calibration_rig) on each
// mission robot alone, then the verifier's own fit (verifier::calibrate).

#include "calibrate_world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "p3at/calibration_rig/calibrate_drive.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/calibration_rig/calibrate_messages.hpp"
#include "p3at/sim/sim_drive_base.hpp"
#include "p3at/sim/world.hpp"
#include "p3at/verifier/calibration.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::crosscheck {

CalibratedModels calibrate_from_world(const mission::Mission& mission, const sim::WorldConfig& world, std::size_t runs,
                                      std::size_t messages, std::uint64_t seed) {
  verifier::CalibrationLog log;
  std::vector<std::string> names;
  std::string note = "each robot alone on open floor, " + std::to_string(runs) + " runs at its own speed:";
  std::int64_t next_id = 0;
  for (std::size_t i = 0; i < mission.robots.size(); ++i) {
    const mission::RobotSpec& spec = mission.robots[i];
    const auto it = std::find_if(world.robots.begin(), world.robots.end(),
                                 [&spec](const sim::RobotConfig& r) { return r.name == spec.name; });
    if (it == world.robots.end()) throw std::runtime_error("the world has no robot named '" + spec.name + "'");
    vipars::ManoeuvrePlan defaults;
    defaults.runs = runs;
    const vipars::ManoeuvrePlan plan = vipars::plan_for_robot(spec, defaults);
    note += " " + spec.name + " " + format_general(plan.speed_mps, 3) + " m/s and " + format_general(plan.spin_rate_degps, 3) +
            " deg/s;";
    sim::WorldConfig open;
    open.radio = world.radio;
    open.robots.push_back(*it);
    // The seed `vipars calibrate --world` gives robot i of its list.
    sim::World w(open, seed ^ (0x9E3779B97F4A7C15ULL * (i + 1)));
    sim::SimDriveBase base(w, 0);
    const vipars::TruthProbe truth = [&w](bool) -> std::optional<verifier::TruePose> {
      const sim::Pose& p = w.robot(0).true_pose();
      return verifier::TruePose{p.x_m, p.y_m, p.theta_rad};
    };
    vipars::drive_manoeuvres(base, spec.name, plan, truth, next_id, log.manoeuvres);
    names.push_back(spec.name);
  }
  vipars::MessagePlan mp;
  mp.count = messages;
  mp.cycle_s = static_cast<double>(sim::kCycleUs) / 1e6;
  log.messages = vipars::measure_messages(world.radio, names, mp, seed);
  note += " spins 180 deg; " + std::to_string(messages) + " messages over the world's radio";

  const verifier::CalibrationResult fit = verifier::calibrate(log);
  verifier::Models models = verifier::to_models(fit);
  models.generated_by = "vipars crosscheck (docs/crosscheck.md): " + note;
  std::string text = "# Written by `vipars crosscheck` from calibration runs on the world's robots alone\n# (" + note + ").\n";
  text += verifier::write_models(models);
  const std::string marker = "\nenvironment:\n";
  const std::size_t at = text.find(marker);
  if (at == std::string::npos) throw std::runtime_error("the models text has no environment block");
  text.insert(at + marker.size(), "  walls_from: world.yaml\n");
  return CalibratedModels{text, verifier::format_calibration_report(fit), note};
}

}  // namespace p3at::crosscheck
