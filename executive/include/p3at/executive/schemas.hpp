#pragma once
/// Motor schemas (docs/executive.md, /work/shared/docs/behaviors.md), written
/// once and generic over the scalar type S so the executive runs them with
/// `double` and the verifier can linearise them (e.g. with Eigen's
/// AutoDiffScalar) when it propagates mixtures of Gaussians.
///
/// Requirements on S: constructible from double; +, -, * and / with S and with
/// double; comparison with double (S < double etc.); and sqrt, atan2 found by
/// argument-dependent lookup or in std. Every function branches on values only
/// where the schema itself is piecewise (dead zone, dropoff, contact, sphere,
/// clamps), so derivatives are exact inside each piece.
///
/// Frames: all vectors here are in one planar frame, the mission (world) frame.
/// behaviors.md states the schemas in the robot's frame; a rotation commutes with
/// every schema, so computing in the world frame and converting once, in
/// vector_to_velocity(), is the same thing.
///
/// Header-only and free of any dependency beyond the standard library.

#include <array>
#include <cmath>
#include <cstddef>
#include <span>

namespace p3at::exec {

/// A planar vector; metres for positions, dimensionless for schema outputs.
template <class S>
struct Vec2 {
  S x{0.0};
  S y{0.0};
};

template <class S>
Vec2<S> operator+(const Vec2<S>& a, const Vec2<S>& b) {
  return Vec2<S>{S(a.x + b.x), S(a.y + b.y)};
}

template <class S>
Vec2<S> operator-(const Vec2<S>& a, const Vec2<S>& b) {
  return Vec2<S>{S(a.x - b.x), S(a.y - b.y)};
}

/// Scales by a plain number (a gain or weight).
template <class S>
Vec2<S> operator*(double k, const Vec2<S>& v) {
  return Vec2<S>{S(k * v.x), S(k * v.y)};
}

/// Euclidean length.
template <class S>
S norm(const Vec2<S>& v) {
  using std::sqrt;
  return S(sqrt(S(v.x * v.x + v.y * v.y)));
}

/// A planar pose: metres, and heading in radians counter-clockwise from +X.
template <class S>
struct Pose {
  S x_m{0.0};
  S y_m{0.0};
  S theta_rad{0.0};
};

/// A velocity command: translational m/s (+ forward), rotational rad/s (+ counter-clockwise).
template <class S>
struct Velocity {
  S trans_mps{0.0};
  S rot_radps{0.0};
};

/// AVOID_OBSTACLES' "effectively infinite" repulsion, for an obstacle at or inside
/// contact distance (robot radius + safety margin): a large finite constant, so a
/// COOP sum stays finite and differentiable. It is 1000 times the largest in-sphere
/// repulsion (1), enough to dominate any sensible COOP weights; vector_to_velocity
/// caps the commanded speed at max speed whatever the vector's length.
inline constexpr double kContactRepulsion = 1000.0;

/// MOVE_TO_GUARDED: towards `goal` with magnitude `gain`, except
///   d <= dead_zone_m                 → zero vector;
///   dead_zone_m < d < dropoff_m      → gain × (d − dead_zone_m) / (dropoff_m − dead_zone_m),
///                                      i.e. 1 at the dropoff edge down to 0 at the dead-zone edge;
/// where d is the distance from `position` to `goal` (metres, same frame).
/// A dropoff at or inside the dead zone means no ramp.
template <class S>
Vec2<S> move_to_guarded(const Vec2<S>& position, const Vec2<S>& goal, double dropoff_m, double dead_zone_m,
                        double gain) {
  const Vec2<S> delta = goal - position;
  const S d = norm(delta);
  if (d <= dead_zone_m) return Vec2<S>{S(0.0), S(0.0)};
  S magnitude = S(gain);
  if (dropoff_m > dead_zone_m && d < dropoff_m) {
    magnitude = S(gain * (d - dead_zone_m) / (dropoff_m - dead_zone_m));
  }
  return Vec2<S>{S(magnitude * delta.x / d), S(magnitude * delta.y / d)};
}

/// AVOID_OBSTACLES: the sum over `obstacles` (points, same frame as `position`) of
/// a repulsion directed from the obstacle to the robot, of magnitude
///   d <= c                     → kContactRepulsion
///   c < d <= c + sphere_m      → (sphere_m − (d − c)) / sphere_m
///   d > c + sphere_m           → 0
/// times `gain`, where d is the obstacle's distance from the robot's centre and
/// c = robot_radius_m + safety_margin_m (a sonar point has no radius of its own,
/// so the robot's radius plays the part of behaviors.md's ρ). An obstacle exactly
/// at the robot's centre has no direction and is skipped.
template <class S>
Vec2<S> avoid_obstacles(std::span<const Vec2<S>> obstacles, const Vec2<S>& position, double sphere_m,
                        double safety_margin_m, double robot_radius_m, double gain) {
  const double contact_m = robot_radius_m + safety_margin_m;
  Vec2<S> sum{S(0.0), S(0.0)};
  for (const Vec2<S>& obstacle : obstacles) {
    const Vec2<S> away = position - obstacle;
    const S d = norm(away);
    if (!(d > 0.0)) continue;
    S magnitude = S(0.0);
    if (d <= contact_m) {
      magnitude = S(kContactRepulsion);
    } else if (sphere_m > 0.0 && d <= contact_m + sphere_m) {
      magnitude = S((sphere_m - (d - contact_m)) / sphere_m);
    } else {
      continue;
    }
    sum = sum + Vec2<S>{S(gain * magnitude * away.x / d), S(gain * magnitude * away.y / d)};
  }
  return sum;
}

/// NOISE: the behavior draws a unit direction (held fixed in world coordinates for
/// its persistence, see noise.hpp); the schema scales it by `gain`.
template <class S>
Vec2<S> noise(const Vec2<S>& direction, double gain) {
  return gain * direction;
}

/// COOP: the weighted vector sum Σ weights[i] × vectors[i].
template <class S, std::size_t N>
Vec2<S> coop(const std::array<Vec2<S>, N>& vectors, const std::array<double, N>& weights) {
  Vec2<S> sum{S(0.0), S(0.0)};
  for (std::size_t i = 0; i < N; ++i) sum = sum + weights[i] * vectors[i];
  return sum;
}

/// Turns a COOP vector (world frame) into a velocity command for a robot heading
/// `heading_rad` (world frame, any number of turns):
///   error = the vector's direction minus the heading, in (−π, π]
///   rot   = clamp(rot_gain × error, −max_rot_radps, +max_rot_radps)
///   trans = max_speed_mps × min(|V|, 1) × max(0, cos(error))
/// so the robot turns towards the vector and slows (to zero beyond ±90°) while
/// the error is large. A zero vector gives a zero command.
template <class S>
Velocity<S> vector_to_velocity(const Vec2<S>& vector, const S& heading_rad, double max_speed_mps,
                               double max_rot_radps, double rot_gain) {
  using std::atan2;
  using std::cos;
  using std::sin;
  const S magnitude = norm(vector);
  if (!(magnitude > 0.0)) return Velocity<S>{S(0.0), S(0.0)};
  // The vector in the robot's frame: forward and leftward components.
  const S c = S(cos(heading_rad));
  const S s = S(sin(heading_rad));
  const S forward = S(c * vector.x + s * vector.y);
  const S left = S(c * vector.y - s * vector.x);
  const S error = S(atan2(left, forward));
  S rot = S(rot_gain * error);
  if (rot > max_rot_radps) rot = S(max_rot_radps);
  if (rot < -max_rot_radps) rot = S(-max_rot_radps);
  const S cos_error = S(forward / magnitude);
  const S speed_fraction = magnitude < 1.0 ? magnitude : S(1.0);
  S trans = S(0.0);
  if (cos_error > 0.0) trans = S(max_speed_mps * speed_fraction * cos_error);
  return Velocity<S>{trans, rot};
}

}  // namespace p3at::exec
