#include "engine/base_motion.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::verifier::engine {
namespace {

// The firmware servoes at a much finer period than the 100 ms cycle; ten steps
// per cycle resolve the ramps and the arc well below the model's uncertainty.
constexpr int kStepsPerCycle = 10;

// Moves `current` toward `wanted` by at most accel*dt when speeding up and
// decel*dt when slowing down; a reversal first stops at zero.
double ramp(double current, double wanted, double accel, double decel, double dt) {
  const bool speeding_up = std::abs(wanted) > std::abs(current) && (current * wanted >= 0.0);
  const double rate = (speeding_up ? accel : decel) * dt;
  if (wanted > current) return std::min(wanted, current + rate);
  return std::max(wanted, current - rate);
}

}  // namespace

CycleIncrement step_cycle(BaseState& base, double command_trans_mps, double command_rot_radps,
                          const Kinematics& k) {
  const double dt = k.cycle_s / kStepsPerCycle;
  const double want_rot = std::clamp(command_rot_radps, -k.max_rot_vel_radps, k.max_rot_vel_radps);
  const double start_theta = base.theta_rad;
  CycleIncrement inc;
  // The heading's cosine and sine are advanced by small rotations rather than
  // recomputed each step (this loop is the verifier's hottest); a step turns
  // at most max_rot_vel * dt (< 0.01 rad), where the series below is exact to
  // double precision.
  double c = std::cos(start_theta), s = std::sin(start_theta);
  auto rotate = [](double& cc, double& ss, double a) {
    const double a2 = a * a;
    const double ca = 1.0 - a2 / 2.0 + a2 * a2 / 24.0;
    const double sa = a * (1.0 - a2 / 6.0 + a2 * a2 / 120.0);
    const double nc = cc * ca - ss * sa;
    ss = ss * ca + cc * sa;
    cc = nc;
  };
  for (int i = 0; i < kStepsPerCycle; ++i) {
    base.trans_mps = ramp(base.trans_mps, command_trans_mps, k.trans_accel_mps2, k.trans_decel_mps2, dt);
    base.rot_radps = ramp(base.rot_radps, want_rot, k.rot_accel_radps2, k.rot_decel_radps2, dt);
    const double ds = base.trans_mps * dt;
    const double dth = base.rot_radps * dt;
    double cm = c, sm = s;
    rotate(cm, sm, dth / 2.0);
    base.x_m += ds * cm;
    base.y_m += ds * sm;
    base.theta_rad += dth;
    rotate(c, s, dth);
    inc.ds_m += ds;
  }
  inc.dtheta_rad = base.theta_rad - start_theta;
  inc.mid_theta_rad = start_theta + inc.dtheta_rad / 2.0;
  return inc;
}

bool at_rest(const BaseState& base) { return std::abs(base.trans_mps) < 1e-6 && std::abs(base.rot_radps) < 1e-6; }

}  // namespace p3at::verifier::engine
