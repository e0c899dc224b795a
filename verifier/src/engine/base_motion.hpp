#pragma once
/// The robot model's nominal base: how a Pioneer's firmware turns the
/// executive's velocity command into odometric motion over one control cycle
/// (acceleration-limited ramps toward the command, integrated in small steps).
/// This is the deterministic part of the paper's Robot_{r,q}(v)(p,d): the
/// odometry q the executive steers by. The true position r is q plus the error
/// state (error_state.hpp).

#include <algorithm>
#include <cmath>

#include "p3at/verifier/models.hpp"

namespace p3at::verifier::engine {

/// Odometric pose (world frame, continuous heading) and the base's actual velocities.
struct BaseState {
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;
  double trans_mps = 0.0, rot_radps = 0.0;
};

/// One cycle's odometric increments, for the error model: distance along the
/// heading, rotation, and the heading halfway through the cycle.
struct CycleIncrement {
  double ds_m = 0.0;
  double dtheta_rad = 0.0;
  double mid_theta_rad = 0.0;
};

/// Advances `base` by one control cycle under the command (trans, rot).
CycleIncrement step_cycle(BaseState& base, double command_trans_mps, double command_rot_radps,
                          const Kinematics& kinematics);

namespace detail {

// The firmware servoes at a much finer period than the 100 ms cycle; ten steps
// per cycle resolve the ramps and the arc well below the model's uncertainty.
inline constexpr int kStepsPerCycle = 10;

// Moves `current` toward `wanted` by at most accel*dt when speeding up and
// decel*dt when slowing down; a reversal first stops at zero.
inline double ramp(double current, double wanted, double accel, double decel, double dt) {
  const bool speeding_up = std::abs(wanted) > std::abs(current) && (current * wanted >= 0.0);
  const double rate = (speeding_up ? accel : decel) * dt;
  if (wanted > current) return std::min(wanted, current + rate);
  return std::max(wanted, current - rate);
}

// Advances the heading's cosine and sine (cc, ss) by a small rotation a: a
// step turns at most max_rot_vel * dt (< 0.01 rad), where the series is exact
// to double precision.
inline void rotate(double& cc, double& ss, double a) {
  const double a2 = a * a;
  const double ca = 1.0 - a2 / 2.0 + a2 * a2 / 24.0;
  const double sa = a * (1.0 - a2 / 6.0 + a2 * a2 / 120.0);
  const double nc = cc * ca - ss * sa;
  ss = ss * ca + cc * sa;
  cc = nc;
}

}  // namespace detail

/// step_cycle() with a say over each substep: `held(candidate)` is asked with
/// the base as it would be after the substep, and when it answers true the
/// substep does not happen and both velocities drop to zero (a stalled
/// base: body_contact.hpp). step_cycle() is this with nothing ever held.
template <class Held>
CycleIncrement step_cycle_held(BaseState& base, double command_trans_mps, double command_rot_radps,
                               const Kinematics& k, Held&& held) {
  const double dt = k.cycle_s / detail::kStepsPerCycle;
  const double want_rot = std::clamp(command_rot_radps, -k.max_rot_vel_radps, k.max_rot_vel_radps);
  const double start_theta = base.theta_rad;
  CycleIncrement inc;
  // The heading's cosine and sine are advanced by small rotations rather than
  // recomputed each step (this loop is the verifier's hottest).
  double c = std::cos(start_theta), s = std::sin(start_theta);
  for (int i = 0; i < detail::kStepsPerCycle; ++i) {
    BaseState next = base;
    next.trans_mps = detail::ramp(base.trans_mps, command_trans_mps, k.trans_accel_mps2, k.trans_decel_mps2, dt);
    next.rot_radps = detail::ramp(base.rot_radps, want_rot, k.rot_accel_radps2, k.rot_decel_radps2, dt);
    const double ds = next.trans_mps * dt;
    const double dth = next.rot_radps * dt;
    double cm = c, sm = s;
    detail::rotate(cm, sm, dth / 2.0);
    next.x_m += ds * cm;
    next.y_m += ds * sm;
    next.theta_rad += dth;
    if (held(static_cast<const BaseState&>(next))) {
      base.trans_mps = 0.0;
      base.rot_radps = 0.0;
      continue;
    }
    base = next;
    detail::rotate(c, s, dth);
    inc.ds_m += ds;
  }
  inc.dtheta_rad = base.theta_rad - start_theta;
  inc.mid_theta_rad = start_theta + inc.dtheta_rad / 2.0;
  return inc;
}

/// True when the base is at rest (both velocities within 1e-6).
bool at_rest(const BaseState& base);

}  // namespace p3at::verifier::engine
