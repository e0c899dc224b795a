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
constexpr double kCycleS = static_cast<double>(kCycleUs) / 1e6;
// The gyro's random stream, offset from the robot's own ("gyro" in ASCII).
constexpr std::uint64_t kGyroStream = 0x6779726F00000000ull;

// Half the footprint's diagonal: no part of a P3-AT is farther from its centre.
const double kP3atRadiusM = std::hypot(kP3atLengthM, kP3atWidthM) / 2.0;

// A rotation, as its cosine and sine.
struct Turn {
  double c = 1.0;
  double s = 0.0;
};

// cos and sin of `angle_rad`, exact to double precision and much cheaper than
// the library's trigonometry for the small angles of a 10 ms physics step: a
// Taylor series whose first term left out is below 3e-17 (a quarter of the
// rounding of 1.0): to the 5th order up to 0.005 rad (half a step's turn at
// 1 rad/s; a P3-AT turns at 0.75 at most), to the 9th order up to 0.1 rad.
// Larger angles use the library.
Turn turn_of(double angle_rad) {
  // Multiplications by the reciprocals (rounded constants, well within the
  // series' precision): a division costs several multiplications.
  constexpr double k2 = 1.0 / 2.0, k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0;
  constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0, k72 = 1.0 / 72.0;
  const double a = angle_rad;
  const double a2 = a * a;
  if (std::abs(a) <= 0.005) return {1.0 - a2 * k2 * (1.0 - a2 * k12), a * (1.0 - a2 * k6 * (1.0 - a2 * k20))};
  if (!(std::abs(a) <= 0.1)) return {std::cos(a), std::sin(a)};
  return {1.0 - a2 * k2 * (1.0 - a2 * k12 * (1.0 - a2 * k30 * (1.0 - a2 * k56))),
          a * (1.0 - a2 * k6 * (1.0 - a2 * k20 * (1.0 - a2 * k42 * (1.0 - a2 * k72))))};
}

// (c, s) turned by `t`: the cosine and sine of the sum of the angles.
void rotate(double& c, double& s, Turn t) {
  const double c2 = c * t.c - s * t.s;
  s = s * t.c + c * t.s;
  c = c2;
}

// Advances `pose` by a forward distance and a rotation, using the mid-step
// heading; (c, s) are the cosine and sine of its heading, and follow it.
void integrate(Pose& pose, double& c, double& s, double distance_m, double rotation_rad) {
  const Turn half = turn_of(rotation_rad / 2.0);
  rotate(c, s, half);  // the mid-step heading
  pose.x_m += distance_m * c;
  pose.y_m += distance_m * s;
  rotate(c, s, half);
  pose.theta_rad = wrap_angle(pose.theta_rad + rotation_rad);
}

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

}  // namespace

SimRobot::SimRobot(RobotConfig config, std::uint64_t world_seed, std::uint64_t stream)
    : config_(std::move(config)),
      rng_(world_seed, stream),
      controller_(config_.limits),
      true_pose_(config_.start) {
  if (config_.gyro) gyro_rng_.emplace(world_seed, kGyroStream + stream);
  sonar_m_.fill(config_.sonar.max_range_m);
  box_ = make_box({true_pose_.x_m, true_pose_.y_m}, std::cos(true_pose_.theta_rad), std::sin(true_pose_.theta_rad),
                  kP3atLengthM, kP3atWidthM);
  const OdometryErrors& err = config_.odometry;
  inv_left_scale_ = 1.0 / err.left_scale;
  inv_right_scale_ = 1.0 / err.right_scale;
  inv_true_track_ = 1.0 / (kNominalTrackM * err.track_ratio);
  // The fastest the centre can move: the controller never exceeds the top
  // velocities, and a wheel really moves at what its encoder measures / scale.
  const double top_wheel_mps =
      config_.limits.max_trans_vel_mps + config_.limits.max_rot_vel_degps * kDegToRad * kNominalTrackM / 2.0;
  const double top_mps = top_wheel_mps / std::min(err.left_scale, err.right_scale);
  cycle_reach_m_ = kP3atRadiusM + top_mps * kCycleS + 0.05;  // 5 cm to spare
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
  odometry_cos_ = 1.0;
  odometry_sin_ = 0.0;
}

void SimRobot::begin_cycle(std::span<const Segment> walls) {
  trans_error_factor_ = 1.0 + rng_.normal(config_.odometry.random_trans_per_unit);
  rot_error_factor_ = 1.0 + rng_.normal(config_.odometry.random_rot_per_unit);
  // Exact values once per update after a move, so the substeps' small
  // rotations never drift (a robot that did not move keeps exact values).
  if (moved_) {
    box_.cos_theta = std::cos(true_pose_.theta_rad);
    box_.sin_theta = std::sin(true_pose_.theta_rad);
    odometry_cos_ = std::cos(odometry_.theta_rad);
    odometry_sin_ = std::sin(odometry_.theta_rad);
    moved_ = false;
  }
  contact_walls_.clear();
  for (const Segment& w : walls) {
    if (segment_within(box_.centre, w, cycle_reach_m_)) contact_walls_.push_back(w);
  }
}

void SimRobot::step(std::int64_t now_us, double dt_s, std::span<const Box> others) {
  controller_.step(now_us, dt_s, odometry_.theta_rad, odometry_distance_m_);
  // The firmware servoes the wheels to what its encoders measure; the ground
  // moves by what the wheels really do, through the effective (slipping) track.
  const double v = controller_.trans_vel_mps();
  const double w = controller_.rot_vel_radps();
  const double left_enc = v - w * kNominalTrackM / 2.0;
  const double right_enc = v + w * kNominalTrackM / 2.0;
  const double left_true = left_enc * inv_left_scale_;
  const double right_true = right_enc * inv_right_scale_;
  const double v_true = (left_true + right_true) / 2.0;
  const double w_true = (right_true - left_true) * inv_true_track_;

  // Standing still or blocked, a gyro still measures its bias and noise,
  // and the firmware still integrates them.
  const auto gyro_at_rest = [&] {
    if (!config_.gyro) return;
    const double rotation = gyro_rotation(now_us, dt_s, 0.0);
    if (rotation == 0.0) return;
    integrate(odometry_, odometry_cos_, odometry_sin_, 0.0, rotation);
    moved_ = true;
  };
  if (std::abs(v_true) < kStillEpsilon && std::abs(w_true) < kStillEpsilon) {
    left_wheel_mps_ = right_wheel_mps_ = 0.0;
    true_trans_vel_mps_ = true_rot_vel_radps_ = 0.0;
    stalled_ = false;
    gyro_at_rest();
    return;
  }
  Pose candidate = true_pose_;
  Box fp = box_;
  integrate(candidate, fp.cos_theta, fp.sin_theta, v_true * dt_s, w_true * dt_s);
  fp.centre = {candidate.x_m, candidate.y_m};
  const bool blocked =
      std::any_of(contact_walls_.begin(), contact_walls_.end(), [&](const Segment& s) { return intersects(fp, s); }) ||
      std::any_of(others.begin(), others.end(), [&](const Box& o) { return intersects(fp, o); });
  if (blocked) {
    // A stalled P3-AT's wheels stop: nothing moves, so the encoders count nothing.
    stalled_ = true;
    controller_.on_stall();
    left_wheel_mps_ = right_wheel_mps_ = 0.0;
    true_trans_vel_mps_ = true_rot_vel_radps_ = 0.0;
    gyro_at_rest();
    return;
  }
  stalled_ = false;
  true_pose_ = candidate;
  box_ = fp;
  moved_ = true;
  true_trans_vel_mps_ = v_true;
  true_rot_vel_radps_ = w_true;
  left_wheel_mps_ = left_enc;
  right_wheel_mps_ = right_enc;
  const double distance = v * dt_s * trans_error_factor_;
  // The heading turns by what the gyro measures if there is one, else by what
  // the encoders say through the nominal track (with this update's error).
  const double rotation = config_.gyro ? gyro_rotation(now_us, dt_s, w_true) : w * dt_s * rot_error_factor_;
  integrate(odometry_, odometry_cos_, odometry_sin_, distance, rotation);
  odometry_distance_m_ += distance;
}

double SimRobot::gyro_rotation(std::int64_t now_us, double dt_s, double true_rate_radps) {
  const GyroModel& g = *config_.gyro;
  const double age_s = static_cast<double>(now_us) * 1e-6;  // powered up with the world, at t = 0
  const double bias_degps = g.bias_degps + g.drift_degps_per_s * age_s;
  const double rate_radps = (1.0 + g.scale_error) * true_rate_radps + bias_degps * kDegToRad +
                            gyro_rng_->normal(g.noise_sd_degps * kDegToRad);
  return rate_radps * dt_s;
}

void SimRobot::update_sonar(std::span<const Segment> walls, std::span<const Box> others) {
  const SonarModel& model = config_.sonar;
  // Only obstacles within reach of some sonar can echo: every sonar sits within
  // the footprint's half-diagonal of the centre and sees max_range_m beyond it.
  const double reach = model.max_range_m + kP3atRadiusM;
  const Vec2 centre = box_.centre;
  // Walls never move: while this robot stands still (half the time in a
  // bounding overwatch), each ray's nearest wall is the one found before.
  const bool same_place = sonar_rays_valid_ && true_pose_.x_m == sonar_pose_.x_m &&
                          true_pose_.y_m == sonar_pose_.y_m && true_pose_.theta_rad == sonar_pose_.theta_rad &&
                          walls.data() == sonar_walls_source_ && walls.size() == sonar_walls_count_;
  if (!same_place) {
    sonar_walls_.clear();
    for (const Segment& s : walls) {
      if (segment_within(centre, s, reach)) sonar_walls_.push_back(s);
    }
    // The heading's cosine and sine are kept by the physics, the sonars' own
    // are constants: rotating is all each of the 16 rays needs.
    const double c = box_.cos_theta;
    const double sn = box_.sin_theta;
    for (std::size_t i = 0; i < kP3atSonars.size(); ++i) {
      const SonarPose& s = kP3atSonars[i];
      SonarRay& ray = sonar_rays_[i];
      ray.origin = {centre.x + c * s.x_m - sn * s.y_m, centre.y + sn * s.x_m + c * s.y_m};
      const double ch = kSonarTrig.cos[i];
      const double sh = kSonarTrig.sin[i];
      ray.direction = {c * ch - sn * sh, sn * ch + c * sh};
      ray.wall_range_m = model.max_range_m;
      ray.wall_hit = false;
      for (const Segment& w : sonar_walls_) {
        ray.wall_hit = ray_hit(ray.origin, ray.direction, w, ray.wall_range_m) || ray.wall_hit;
      }
    }
    sonar_pose_ = true_pose_;
    sonar_walls_source_ = walls.data();
    sonar_walls_count_ = walls.size();
    sonar_rays_valid_ = true;
  }
  // Other robots move: every update tests them, each first against its
  // bounding circle (a ray that misses it misses the four edges).
  sonar_boxes_.clear();
  sonar_edges_.clear();
  for (const Box& b : others) {
    const double dx = b.centre.x - centre.x;
    const double dy = b.centre.y - centre.y;
    const double r = reach + b.radius_m;
    if (dx * dx + dy * dy > r * r) continue;
    sonar_boxes_.push_back(b);
    Segment edges[4];
    box_edges(b, edges);
    sonar_edges_.insert(sonar_edges_.end(), edges, edges + 4);
  }
  for (std::size_t i = 0; i < kP3atSonars.size(); ++i) {
    const SonarRay& ray = sonar_rays_[i];
    double nearest = ray.wall_range_m;
    bool hit = ray.wall_hit;
    for (std::size_t b = 0; b < sonar_boxes_.size(); ++b) {
      if (!ray_may_hit(ray.origin, ray.direction, sonar_boxes_[b], nearest)) continue;
      for (std::size_t e = 4 * b; e < 4 * b + 4; ++e) {
        hit = ray_hit(ray.origin, ray.direction, sonar_edges_[e], nearest) || hit;
      }
    }
    sonar_m_[i] = hit ? std::clamp(nearest + rng_.normal(model.noise_sd_m), 0.0, model.max_range_m) : model.max_range_m;
  }
}

}  // namespace p3at::sim
