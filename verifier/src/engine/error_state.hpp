#pragma once
/// The true pose's error relative to odometry, e = r - q (x, y, heading), as a
/// Gaussian: the random part of the paper's Robot_{r,q} template, propagated
/// through each cycle's odometric increments by the calibrated z(u, t)
/// (MotionError). Linear in e except through the heading, which is linearised
/// about the mean (an extended-Kalman prediction step without updates: the
/// robot never observes its true position).

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::engine {

struct ErrorState {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();   ///< (ex_m, ey_m, etheta_rad)
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

/// Applies one cycle's increments, the odometric heading at the cycle's middle
/// being `inc.mid_theta_rad`.
void propagate(ErrorState& error, const CycleIncrement& inc, const MotionError& model);

/// Moment-matched combination of weighted error states (weights need not sum to 1).
ErrorState combine(const ErrorState* states, const double* weights, std::size_t n);

}  // namespace p3at::verifier::engine
