#include "engine/error_state.hpp"

#include <cmath>

namespace p3at::verifier::engine {

void propagate(ErrorState& e, const CycleIncrement& inc, const MotionError& m) {
  const double ds = inc.ds_m;
  const double dth = inc.dtheta_rad;
  // Heading error grows by the rotation-scale error of this cycle's turn and by drift.
  const double eth_mid = e.mean(2) + ((m.rot_scale - 1.0) * dth + m.drift_rad_per_m * ds) / 2.0;
  const double true_heading = inc.mid_theta_rad + eth_mid;
  const double c_true = std::cos(true_heading), s_true = std::sin(true_heading);
  const double c_odo = std::cos(inc.mid_theta_rad), s_odo = std::sin(inc.mid_theta_rad);

  // Mean: true step minus odometric step; a turn's own forward motion is
  // all error (the odometry counts none).
  const double turn_move = m.trans_per_rad_m * dth;
  e.mean(0) += ds * (m.trans_scale * c_true - c_odo) + turn_move * c_true;
  e.mean(1) += ds * (m.trans_scale * s_true - s_odo) + turn_move * s_true;
  e.mean(2) += (m.rot_scale - 1.0) * dth + m.drift_rad_per_m * ds;

  // Jacobian of the step with respect to e (only the heading error moves x, y).
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  f(0, 2) = -(ds * m.trans_scale + turn_move) * s_true;
  f(1, 2) = (ds * m.trans_scale + turn_move) * c_true;
  // Random increments: along the true heading for distance, on the heading for rotation.
  const double var_s = m.trans_var_per_m * std::abs(ds) + m.trans_rel_var * ds * ds;
  const double var_th = m.rot_var_per_rad * std::abs(dth) + m.heading_var_per_m * std::abs(ds) + m.rot_rel_var * dth * dth;
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
  q(0, 0) = var_s * c_true * c_true;
  q(0, 1) = q(1, 0) = var_s * c_true * s_true;
  q(1, 1) = var_s * s_true * s_true;
  q(2, 2) = var_th;
  e.cov = f * e.cov * f.transpose() + q;
}

ErrorState combine(const ErrorState* states, const double* weights, std::size_t n) {
  ErrorState out;
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) total += weights[i];
  if (!(total > 0.0)) return n > 0 ? states[0] : out;
  for (std::size_t i = 0; i < n; ++i) out.mean += (weights[i] / total) * states[i].mean;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = states[i].mean - out.mean;
    out.cov += (weights[i] / total) * (states[i].cov + d * d.transpose());
  }
  return out;
}

}  // namespace p3at::verifier::engine
