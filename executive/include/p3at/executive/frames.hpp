#pragma once
/// Planar pose algebra used to express odometry in the mission frame:
///   mission pose = start ⊕ (origin⁻¹ ⊕ odometry)
/// where `start` is the robot's start pose in the mission file and `origin` the
/// odometry reading when the mission began. Headings stay continuous (no wrap),
/// so HasTurned and the verifier see the accumulated turn.

#include <cmath>

#include "p3at/executive/schemas.hpp"

namespace p3at::exec {

/// a ⊕ b: pose b, given relative to pose a, expressed in a's parent frame.
template <class S>
Pose<S> compose(const Pose<S>& a, const Pose<S>& b) {
  using std::cos;
  using std::sin;
  const S c = S(cos(a.theta_rad));
  const S s = S(sin(a.theta_rad));
  return Pose<S>{S(a.x_m + c * b.x_m - s * b.y_m), S(a.y_m + s * b.x_m + c * b.y_m), S(a.theta_rad + b.theta_rad)};
}

/// a⁻¹ ⊕ b: pose b expressed relative to pose a (both in the same frame).
template <class S>
Pose<S> relative(const Pose<S>& a, const Pose<S>& b) {
  using std::cos;
  using std::sin;
  const S c = S(cos(a.theta_rad));
  const S s = S(sin(a.theta_rad));
  const S dx = S(b.x_m - a.x_m);
  const S dy = S(b.y_m - a.y_m);
  return Pose<S>{S(c * dx + s * dy), S(c * dy - s * dx), S(b.theta_rad - a.theta_rad)};
}

/// An angle wrapped into (−π, π].
inline double wrap_angle_rad(double angle_rad) {
  constexpr double kPi = 3.14159265358979323846;
  double wrapped = std::remainder(angle_rad, 2.0 * kPi);
  if (wrapped <= -kPi) wrapped += 2.0 * kPi;
  return wrapped;
}

}  // namespace p3at::exec
