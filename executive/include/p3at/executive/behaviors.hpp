#pragma once
/// The mission's behaviors as the executive runs them (docs/executive.md).
/// go_to_guarded_vector() is generic over the scalar type like schemas.hpp, so the
/// verifier can use exactly the COOP the executive runs.

#include <algorithm>
#include <array>
#include <span>

#include "p3at/executive/schemas.hpp"
#include "p3at/mission/mission.hpp"

namespace p3at::exec {

/// Robot-specific constants the behaviors need beyond the mission file.
struct BehaviorConfig {
  double max_speed_mps = 0.3;        ///< translational cap (the mission's max_speed_mps)
  double max_rot_radps = 0.75;       ///< rotational cap (MobileSim's P3-AT, 43 deg/s)
  double rot_gain = 1.5;             ///< rad/s commanded per rad of heading error
  /// AVOID_OBSTACLES' robot radius: the half-diagonal of the P3-AT's 626 × 505 mm
  /// body (ARIA's 500 mm RobotRadius is a padded figure).
  double robot_radius_m = 0.4;
};

/// GoToGuarded's COOP vector (world frame): move_gain × MOVE_TO_GUARDED(goal)
/// + avoid_gain × AVOID_OBSTACLES(obstacles) + noise_gain × NOISE(noise_direction),
/// all with unit schema gains, the mission's gains being the COOP weights.
template <class S>
Vec2<S> go_to_guarded_vector(const mission::GoToGuardedParams& params, const Vec2<S>& position,
                             std::span<const Vec2<S>> obstacles, const Vec2<S>& noise_direction,
                             double robot_radius_m) {
  const Vec2<S> goal{S(params.goal.x_m), S(params.goal.y_m)};
  const std::array<Vec2<S>, 3> members{
      move_to_guarded(position, goal, params.dropoff_m, params.dead_zone_m, 1.0),
      avoid_obstacles(obstacles, position, params.sphere_m, params.safety_margin_m, robot_radius_m, 1.0),
      noise(noise_direction, 1.0),
  };
  return coop(members, std::array<double, 3>{params.move_gain, params.avoid_gain, params.noise_gain});
}

/// GoToGuarded's velocity command for a robot at `pose` (world frame).
template <class S>
Velocity<S> go_to_guarded(const mission::GoToGuardedParams& params, const Pose<S>& pose,
                          std::span<const Vec2<S>> obstacles, const Vec2<S>& noise_direction,
                          const BehaviorConfig& config) {
  const Vec2<S> vector =
      go_to_guarded_vector(params, Vec2<S>{pose.x_m, pose.y_m}, obstacles, noise_direction, config.robot_radius_m);
  return vector_to_velocity(vector, pose.theta_rad, config.max_speed_mps, config.max_rot_radps, config.rot_gain);
}

/// SPIN's command: rotate in place at the mission's rate, limited to ±max_rot_radps.
inline Velocity<double> spin_command(const mission::SpinParams& params, const BehaviorConfig& config) {
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  const double rate_radps = std::clamp(params.rate_deg_s * kDegToRad, -config.max_rot_radps, config.max_rot_radps);
  return Velocity<double>{0.0, rate_radps};
}

}  // namespace p3at::exec
