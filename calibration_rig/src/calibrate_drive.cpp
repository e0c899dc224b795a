// drive_manoeuvres(): straight runs and spins on a hal::DriveBase, one row
// per control cycle from rest to rest. Steering is by odometry alone (the
// robot is told to stop when its odometry says the distance or angle is
// done), exactly as the executive steers; the true pose is only recorded.

#include "p3at/calibration_rig/calibrate_drive.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

namespace p3at::vipars {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// Reported speeds below these count as standing still.
constexpr double kRestTransMps = 0.002;
constexpr double kRestRotRadps = 0.2 * kDeg;
// Consecutive still cycles that make "at rest".
constexpr int kRestCycles = 2;
constexpr int kUpdateTimeoutMs = 1000;
// Time allowed to reach rest before a manoeuvre, seconds.
constexpr double kSettleS = 10.0;

struct Step {
  verifier::ManoeuvreKind kind;
  double command;  ///< m/s or rad/s, signed
  double amount;   ///< m or rad, positive
};

double wrap(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

bool still(const hal::DriveState& s) {
  return std::abs(s.trans_vel_mps) < kRestTransMps && std::abs(s.rot_vel_radps) < kRestRotRadps;
}

class Driver {
 public:
  Driver(hal::DriveBase& base, std::string robot, const TruthProbe& truth, double speedup)
      : base_(base), robot_(std::move(robot)), truth_(truth), speedup_(speedup), origin_us_(base.state().stamp_us) {}

  verifier::Manoeuvre run(const Step& step, std::int64_t id) {
    settle();
    verifier::Manoeuvre m;
    m.robot = robot_;
    m.id = id;
    m.kind = step.kind;
    const hal::Pose2 start = base_.state().odometry;
    const bool straight = step.kind == verifier::ManoeuvreKind::straight;
    double command = step.command;
    double turned = 0.0;
    double last_theta = start.theta_rad;
    int still_cycles = 0;
    // Generous: the nominal time at the commanded speed, three times over, plus ramps.
    const double limit_s = 3.0 * step.amount / std::abs(step.command) + 10.0;
    const double t0 = seconds();
    while (true) {
      const hal::DriveState& s = base_.state();
      turned += wrap(s.odometry.theta_rad - last_theta);
      last_theta = s.odometry.theta_rad;
      const double progress =
          straight ? std::abs((s.odometry.x_m - start.x_m) * std::cos(start.theta_rad) +
                              (s.odometry.y_m - start.y_m) * std::sin(start.theta_rad))
                   : std::abs(turned);
      if (progress >= step.amount) command = 0.0;
      still_cycles = command == 0.0 && still(s) ? still_cycles + 1 : 0;
      const bool first = m.rows.empty();
      const bool last = still_cycles >= kRestCycles;
      verifier::CycleRow row;
      row.t_s = seconds();
      row.cmd_trans_mps = straight ? command : 0.0;
      row.cmd_rot_radps = straight ? 0.0 : command;
      row.odom_x_m = s.odometry.x_m;
      row.odom_y_m = s.odometry.y_m;
      row.odom_theta_rad = s.odometry.theta_rad;
      row.truth = truth_(first || last);
      if ((first || last) && !row.truth && truth_expected_) {
        throw DriveError(robot_ + ": no true pose available at the " + (first ? "start" : "end") + " of manoeuvre " +
                         std::to_string(id));
      }
      m.rows.push_back(row);
      if (last) break;
      command_velocity(row.cmd_trans_mps, row.cmd_rot_radps);
      if (seconds() - t0 > limit_s) {
        (void)base_.stop();
        throw DriveError(robot_ + ": " + verifier::to_string(step.kind) + " " + std::to_string(id) +
                         " did not finish within " + std::to_string(limit_s) + " s (progress " +
                         std::to_string(progress) + " of " + std::to_string(step.amount) + ")");
      }
      next_update();
    }
    return m;
  }

  void expect_truth(bool expected) { truth_expected_ = expected; }

 private:
  // The robot's time since the calibration began: the base's clock, scaled
  // when the robot runs faster than it.
  double seconds() const { return static_cast<double>(base_.state().stamp_us - origin_us_) / 1e6 * speedup_; }

  void command_velocity(double trans, double rot) {
    if (const Status st = base_.set_velocity(trans, rot); !st) {
      (void)base_.stop();
      throw DriveError(robot_ + ": the base refused a velocity command: " + st.error().message);
    }
  }

  void next_update() {
    for (int tries = 0; tries < 5; ++tries) {
      const Result<bool> updated = base_.wait_for_update(kUpdateTimeoutMs);
      if (!updated) throw DriveError(robot_ + ": " + updated.error().message);
      const hal::DriveState& s = base_.state();
      if (s.link != hal::LinkState::ok) {
        throw DriveError(robot_ + ": drive link " + hal::to_string(s.link) +
                         (s.why_stopped.empty() ? std::string() : ": " + s.why_stopped));
      }
      if (s.left_stall || s.right_stall) {
        (void)base_.stop();
        throw DriveError(robot_ + ": stalled (an obstacle in the way? calibrate in open space)");
      }
      if (*updated) return;
    }
    throw DriveError(robot_ + ": no update from the base for " + std::to_string(5 * kUpdateTimeoutMs) + " ms");
  }

  // Commands zero until the base has stood still for a few cycles.
  void settle() {
    const double t0 = seconds();
    int still_cycles = 0;
    while (still_cycles < kRestCycles) {
      command_velocity(0.0, 0.0);
      next_update();
      still_cycles = still(base_.state()) ? still_cycles + 1 : 0;
      if (seconds() - t0 > kSettleS) throw DriveError(robot_ + ": did not come to rest within 10 s");
    }
  }

  hal::DriveBase& base_;
  std::string robot_;
  const TruthProbe& truth_;
  double speedup_ = 1.0;
  std::int64_t origin_us_ = 0;
  bool truth_expected_ = false;
};

}  // namespace

void drive_manoeuvres(hal::DriveBase& base, const std::string& robot, const ManoeuvrePlan& plan,
                      const TruthProbe& truth, std::int64_t& next_id, std::vector<verifier::Manoeuvre>& out) {
  using verifier::ManoeuvreKind;
  const double rate = plan.spin_rate_degps * kDeg;
  const double fast = plan.fast_spin_degps * kDeg;
  const double angle = plan.spin_deg * kDeg;
  const Step steps[] = {
      {ManoeuvreKind::straight, plan.speed_mps, plan.distance_m},
      {ManoeuvreKind::spin, rate, angle},
      {ManoeuvreKind::straight, plan.speed_mps / 2.0, plan.distance_m},
      {ManoeuvreKind::spin, -rate / 2.0, angle},
      {ManoeuvreKind::spin, fast, angle},
      {ManoeuvreKind::spin, -fast, angle},
  };
  Driver driver(base, robot, truth, plan.speedup);
  driver.expect_truth(static_cast<bool>(truth(true)));
  for (std::size_t run = 0; run < plan.runs; ++run) {
    for (const Step& step : steps) out.push_back(driver.run(step, next_id++));
  }
  (void)base.stop();
}

ManoeuvrePlan plan_for_robot(const mission::RobotSpec& robot, ManoeuvrePlan flags) {
  flags.speed_mps = std::clamp(robot.max_speed_mps, 0.01, 2.0);
  for (const mission::State& s : robot.states) {
    if (s.kind() == mission::BehaviorKind::spin) {
      flags.spin_rate_degps = std::clamp(std::abs(std::get<mission::SpinParams>(s.behavior).rate_deg_s), 1.0, 300.0);
      break;
    }
  }
  return flags;
}

}  // namespace p3at::vipars
