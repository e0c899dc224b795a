// calibrate(): a calibration log into robot models and delay mixtures.
// Checks that every robot has enough usable manoeuvres, then hands each
// robot's straights and spins to the motion fit, all its manoeuvres to the
// kinematics fit, and the messages' delays to the delay fit.

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/fit_parts.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::verifier {
namespace {

using calibration_detail::Measure;

// A manoeuvre this short says more about the measuring than about the robot.
constexpr double kMinStraightM = 0.1;
constexpr double kMinSpinRad = 0.1;
constexpr std::size_t kMinRuns = 2;
// The longest delay a models file holds (1e7 ms).
constexpr double kMaxDelayS = 1e4;

std::string where(const Manoeuvre& m) {
  return m.robot + " " + to_string(m.kind) + " " + std::to_string(m.id) +
         (m.rows.empty() || m.rows.front().line == 0
              ? std::string()
              : " (lines " + std::to_string(m.rows.front().line) + "-" + std::to_string(m.rows.back().line) + ")");
}

// A fit a models file cannot hold (values overflowing, a robot turning
// against its odometry) says the log is wrong, not the robot: refuse it here
// rather than write a file the verifier would refuse.
void check_fit(const RobotCalibration& r) {
  for (const ParameterFit& f : r.fits) {
    if (!std::isfinite(f.value)) {
      throw CalibrationError(r.model.name + ": " + f.name + " came out as " + std::to_string(f.value) +
                             " (are the log's values in metres, seconds and radians?)");
    }
  }
  const MotionError& e = r.model.motion;
  for (const auto& [name, scale] : {std::pair{"trans_scale", e.trans_scale}, std::pair{"rot_scale", e.rot_scale}}) {
    if (!(scale > 0.0 && scale <= 10.0)) {
      throw CalibrationError(r.model.name + ": " + name + " came out as " + std::to_string(scale) +
                             " (expected 0 < x <= 10: does the log's odometry turn and move the way the robot did?)");
    }
  }
}

RobotCalibration calibrate_robot(const std::string& robot, const std::vector<const Manoeuvre*>& manoeuvres,
                                 const CalibrationOptions& options, std::vector<std::string>& warnings) {
  std::vector<Measure> straights;
  std::vector<Measure> spins;
  std::size_t without_truth = 0;
  for (const Manoeuvre* m : manoeuvres) {
    if (m->rows.size() < 2) throw CalibrationError(where(*m) + ": a manoeuvre needs at least two rows (start and end)");
    const bool start = m->rows.front().truth.has_value();
    const bool end = m->rows.back().truth.has_value();
    if (start != end) {
      throw CalibrationError(where(*m) + ": a true pose at its " + (start ? "start" : "end") + " but not at its " +
                             (start ? "end" : "start") + " (both ends are needed)");
    }
    const Measure measured = calibration_detail::measure(*m);
    if (!measured.has_truth) {
      ++without_truth;
      continue;
    }
    if (m->kind == ManoeuvreKind::straight) {
      if (!(std::abs(measured.odo_dist_m) >= kMinStraightM)) {
        throw CalibrationError(where(*m) + ": moved only " + std::to_string(measured.odo_dist_m) +
                               " m by odometry (a straight run needs at least " + std::to_string(kMinStraightM) + " m)");
      }
      straights.push_back(measured);
    } else {
      if (!(std::abs(measured.odo_rot_rad) >= kMinSpinRad)) {
        throw CalibrationError(where(*m) + ": turned only " + std::to_string(measured.odo_rot_rad * 180.0 / std::numbers::pi) +
                               " deg by odometry (a spin needs at least " +
                               std::to_string(kMinSpinRad * 180.0 / std::numbers::pi) + " deg)");
      }
      spins.push_back(measured);
    }
  }
  if (straights.size() < kMinRuns || spins.size() < kMinRuns) {
    throw CalibrationError(robot + ": " + std::to_string(straights.size()) + " straight run(s) and " +
                           std::to_string(spins.size()) +
                           " spin(s) with true poses at both ends; the motion error needs at least " +
                           std::to_string(kMinRuns) + " of each (10 or more for useful standard errors)");
  }
  if (without_truth > 0) {
    warnings.push_back(robot + ": " + std::to_string(without_truth) +
                       " manoeuvre(s) without true poses used for the kinematics only");
  }

  RobotCalibration out;
  out.model.name = robot;
  out.straights = straights.size();
  out.spins = spins.size();
  calibration_detail::KinematicsFit k = calibration_detail::fit_kinematics(robot, manoeuvres, options.kinematics_defaults);
  calibration_detail::MotionFit e = calibration_detail::fit_motion(straights, spins);
  out.model.kinematics = k.kinematics;
  // The speed the motion error was measured at: the fastest command of the
  // straight runs. A mission faster than that is outside the fit (the
  // verifier lists it as an approximation, approximations.hpp).
  out.model.kinematics.calibrated_speed_mps = 0.0;
  for (const Manoeuvre* m : manoeuvres) {
    if (m->kind != ManoeuvreKind::straight) continue;
    for (const CycleRow& row : m->rows) {
      out.model.kinematics.calibrated_speed_mps = std::max(out.model.kinematics.calibrated_speed_mps, std::abs(row.cmd_trans_mps));
    }
  }
  out.model.motion = e.motion;
  out.fits = std::move(k.fits);
  out.fits.insert(out.fits.end(), e.fits.begin(), e.fits.end());
  warnings.insert(warnings.end(), k.warnings.begin(), k.warnings.end());
  check_fit(out);
  return out;
}

}  // namespace

CalibrationResult calibrate(const CalibrationLog& log, const CalibrationOptions& options) {
  CalibrationResult result;
  std::vector<std::string> order;
  std::map<std::string, std::vector<const Manoeuvre*>> by_robot;
  for (const Manoeuvre& m : log.manoeuvres) {
    auto [it, inserted] = by_robot.try_emplace(m.robot);
    if (inserted) order.push_back(m.robot);
    it->second.push_back(&m);
  }
  if (order.empty()) throw CalibrationError("the log has no manoeuvres (straight runs and spins): nothing to calibrate");
  for (const std::string& robot : order) {
    result.robots.push_back(calibrate_robot(robot, by_robot[robot], options, result.warnings));
  }

  std::vector<double> delivery;
  std::vector<double> ack;
  std::size_t delivery_lost = 0;
  std::size_t ack_lost = 0;
  for (const MessageRow& m : log.messages) {
    const double delivery_s = (m.delivered_s ? *m.delivered_s : m.sent_s) - m.sent_s;
    const double ack_s = (m.acked_s ? *m.acked_s : m.sent_s) - m.sent_s;
    if (!(delivery_s >= 0.0 && ack_s >= 0.0 && delivery_s <= kMaxDelayS && ack_s <= kMaxDelayS)) {
      throw CalibrationError("message " + std::to_string(m.id) + " of " + m.sender +
                             (m.line > 0 ? " (line " + std::to_string(m.line) + ")" : std::string()) +
                             ": delivered and acknowledged must be 0 to " + std::to_string(kMaxDelayS) +
                             " s after it was sent (are the times in seconds?)");
    }
    if (m.delivered_s) {
      delivery.push_back(*m.delivered_s - m.sent_s);
    } else {
      ++delivery_lost;
    }
    if (m.acked_s) {
      ack.push_back(*m.acked_s - m.sent_s);
    } else {
      ++ack_lost;
    }
  }
  result.delivery = fit_delay(delivery, delivery_lost, options.max_delay_components);
  result.ack = fit_delay(ack, ack_lost, options.max_delay_components);
  if (log.messages.empty()) {
    result.warnings.push_back("no message rows: the team link is left out of the models (an ideal link, no delay)");
  }
  // Whatever else the data holds, the result must be a models file the
  // verifier loads: its ranges are the loader's, checked by the loader.
  try {
    (void)parse_models(write_models(to_models(result)), "calibration", "");
  } catch (const ModelsError& e) {
    throw CalibrationError("the fit is outside the models file's ranges: " + e.detail() +
                           " (are the log's values in metres, seconds and radians?)");
  } catch (const std::invalid_argument& e) {
    throw CalibrationError(std::string("the fit cannot be written: ") + e.what());
  }
  if (delivery_lost + ack_lost > 0) {
    result.warnings.push_back(std::to_string(delivery_lost) + " message(s) never delivered and " +
                              std::to_string(ack_lost) +
                              " never acknowledged: not in the delay mixtures (the models have no loss)");
  }
  return result;
}

Models to_models(const CalibrationResult& result) {
  Models models;
  for (const RobotCalibration& r : result.robots) models.robots.push_back(r.model);
  models.comm.delivery_s = result.delivery.mixture;
  models.comm.ack_s = result.ack.mixture;
  return models;
}

}  // namespace p3at::verifier
