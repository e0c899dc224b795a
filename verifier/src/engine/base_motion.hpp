#pragma once
/// The robot model's nominal base: how a Pioneer's firmware turns the
/// executive's velocity command into odometric motion over one control cycle
/// (acceleration-limited ramps toward the command, integrated in small steps).
/// This is the deterministic part of the paper's Robot_{r,q}(v)(p,d): the
/// odometry q the executive steers by. The true position r is q plus the error
/// state (error_state.hpp).

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

/// True when the base is at rest (both velocities within 1e-6).
bool at_rest(const BaseState& base);

}  // namespace p3at::verifier::engine
