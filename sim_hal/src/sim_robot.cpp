#include "p3at/sim/sim_robot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

namespace p3at::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kStillEpsilon = 1e-9;

// Advances `pose` by a forward distance and a rotation, using the mid-step heading.
Pose integrate(const Pose& pose, double distance_m, double rotation_rad) {
  const double mid = pose.theta_rad + rotation_rad / 2.0;
  return {pose.x_m + distance_m * std::cos(mid), pose.y_m + distance_m * std::sin(mid),
          wrap_angle(pose.theta_rad + rotation_rad)};
}

}  // namespace

SimRobot::SimRobot(RobotConfig config, std::uint64_t world_seed, std::uint64_t stream)
    : config_(std::move(config)),
      rng_(world_seed, stream),
      controller_(config_.limits),
      true_pose_(config_.start) {
  sonar_m_.fill(config_.sonar.max_range_m);
}

Pose SimRobot::odometry_in_world() const {
  const Vec2 p = to_world(config_.start, {odometry_.x_m, odometry_.y_m});
  return {p.x, p.y, wrap_angle(config_.start.theta_rad + odometry_.theta_rad)};
}

bool SimRobot::moving() const {
  return std::abs(left_wheel_mps_) > kStillEpsilon || std::abs(right_wheel_mps_) > kStillEpsilon;
}

void SimRobot::reset_odometry() {
  controller_.on_heading_reset(odometry_.theta_rad);
  odometry_ = Pose{};
}

void SimRobot::begin_cycle() {
  trans_error_factor_ = 1.0 + rng_.gaussian(config_.odometry.random_trans_per_unit);
  rot_error_factor_ = 1.0 + rng_.gaussian(config_.odometry.random_rot_per_unit);
}

void SimRobot::step(std::int64_t now_us, double dt_s, std::span<const Segment> walls,
                    std::span<const Footprint> others) {
  controller_.step(now_us, dt_s, odometry_.theta_rad, odometry_distance_m_);
  const OdometryErrors& err = config_.odometry;
  // The firmware servoes the wheels to what its encoders measure; the ground
  // moves by what the wheels really do, through the effective (slipping) track.
  const double v = controller_.trans_vel_mps();
  const double w = controller_.rot_vel_radps();
  const double left_enc = v - w * kNominalTrackM / 2.0;
  const double right_enc = v + w * kNominalTrackM / 2.0;
  const double left_true = left_enc / err.left_scale;
  const double right_true = right_enc / err.right_scale;
  const double v_true = (left_true + right_true) / 2.0;
  const double w_true = (right_true - left_true) / (kNominalTrackM * err.track_ratio);

  if (std::abs(v_true) < kStillEpsilon && std::abs(w_true) < kStillEpsilon) {
    left_wheel_mps_ = right_wheel_mps_ = 0.0;
    true_trans_vel_mps_ = true_rot_vel_radps_ = 0.0;
    stalled_ = false;
    return;
  }
  const Pose candidate = integrate(true_pose_, v_true * dt_s, w_true * dt_s);
  const Footprint fp{candidate, kP3atLengthM, kP3atWidthM};
  const bool blocked = std::any_of(walls.begin(), walls.end(), [&](const Segment& s) { return intersects(fp, s); }) ||
                       std::any_of(others.begin(), others.end(), [&](const Footprint& o) { return intersects(fp, o); });
  if (blocked) {
    // A stalled P3-AT's wheels stop: nothing moves, so the encoders count nothing.
    stalled_ = true;
    controller_.on_stall();
    left_wheel_mps_ = right_wheel_mps_ = 0.0;
    true_trans_vel_mps_ = true_rot_vel_radps_ = 0.0;
    return;
  }
  stalled_ = false;
  true_pose_ = candidate;
  true_trans_vel_mps_ = v_true;
  true_rot_vel_radps_ = w_true;
  left_wheel_mps_ = left_enc;
  right_wheel_mps_ = right_enc;
  const double distance = v * dt_s * trans_error_factor_;
  odometry_ = integrate(odometry_, distance, w * dt_s * rot_error_factor_);
  odometry_distance_m_ += distance;
}

namespace {
// cos and sin of each sonar's mounting heading, computed once.
struct SonarTrig {
  std::array<double, kP3atSonars.size()> cos{}, sin{};
  SonarTrig() {
    for (std::size_t i = 0; i < kP3atSonars.size(); ++i) {
      cos[i] = std::cos(kP3atSonars[i].heading_deg * kDegToRad);
      sin[i] = std::sin(kP3atSonars[i].heading_deg * kDegToRad);
    }
  }
};
const SonarTrig kSonarTrig;
const auto& kSonarCos = kSonarTrig.cos;
const auto& kSonarSin = kSonarTrig.sin;
}  // namespace

void SimRobot::update_sonar(std::span<const Segment> obstacles) {
  const SonarModel& model = config_.sonar;
  // Only obstacles within reach of some sonar can echo: every sonar sits within
  // the footprint's half-diagonal of the centre and sees max_range_m beyond it.
  // Filtering first keeps ray casting cheap in large worlds; results are unchanged.
  const double reach = model.max_range_m + std::hypot(kP3atLengthM, kP3atWidthM) / 2.0;
  const Vec2 centre{true_pose_.x_m, true_pose_.y_m};
  nearby_.clear();
  for (const Segment& s : obstacles) {
    if (distance_sq_to_segment(centre, s.a, s.b) <= reach * reach) nearby_.push_back(s);
  }
  obstacles = nearby_;
  // One sine and cosine of the heading for all 16 sonars (the sonar headings'
  // own are constants): rotating is cheaper than 32 more trigonometric calls.
  const double c = std::cos(true_pose_.theta_rad);
  const double sn = std::sin(true_pose_.theta_rad);
  for (std::size_t i = 0; i < kP3atSonars.size(); ++i) {
    const SonarPose& s = kP3atSonars[i];
    const Vec2 origin{true_pose_.x_m + c * s.x_m - sn * s.y_m, true_pose_.y_m + sn * s.x_m + c * s.y_m};
    const double ch = kSonarCos[i];
    const double sh = kSonarSin[i];
    const auto hit = ray_cast_dir(origin, {c * ch - sn * sh, sn * ch + c * sh}, obstacles, model.max_range_m);
    sonar_m_[i] = hit ? std::clamp(*hit + rng_.gaussian(model.noise_sd_m), 0.0, model.max_range_m) : model.max_range_m;
  }
}

}  // namespace p3at::sim
