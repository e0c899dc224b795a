#pragma once
/// A message interrupting a motion state: a Notified transition out of a
/// GoToGuarded or a Spin (a robot recalled mid-leg, a patrol left mid-beat).
/// Where the robot is when the message takes it out of the state is the race
/// between the message's arrival and the leg's progress: given the time τ
/// since the state's entry at which the transition fires (a mixture), the
/// robot is where each NOISE path's trajectory (leg_trajectory.hpp) is at τ.
/// The sequencer splits the branch into a few bins of τ (equal probability),
/// and each bin continues from the paths' poses at the bin's mean time, with
/// the motion within the bin added as a spread.

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "engine/error_state.hpp"
#include "engine/leg_trajectory.hpp"
#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {

/// One bin of the interruption time and where it finds the robot.
struct InterruptionBin {
  double probability = 0.0;     ///< of τ falling in the bin
  double tau_mean_s = 0.0;      ///< E[τ | bin]
  double tau_var_s2 = 0.0;      ///< Var[τ | bin]
  BaseState base;               ///< mean odometric pose (and velocities) over the paths at tau_mean_s
  ErrorState error;             ///< the paths' errors there, moment-matched
  /// Each path's odometric position minus the mean, as equally likely points
  /// (the paths' own when they are equally likely, else slabs of them).
  std::vector<Eigen::Vector2d> offsets;
  /// Each path's offset, weight and heading (for the next state's start points).
  std::vector<Eigen::Vector2d> path_offsets;
  std::vector<double> weights;
  std::vector<double> headings;
  /// The covariance of `offsets`.
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  /// The motion within the bin: Σ_j w_j v_j v_jᵀ Var[τ | bin], v_j path j's velocity there.
  Eigen::Matrix2d within = Eigen::Matrix2d::Zero();
};

/// The pose of path j after `t_s` seconds in the state (interpolated between
/// cycles; held at the path's last recorded cycle beyond it).
TrajectoryPoint pose_at(const LegTrajectory& leg, std::size_t path, double t_s);

/// The paths of `leg` that got stuck (`stuck == true`) or that did not, their
/// weights renormalised: where a robot is, given which of the two it is on.
/// Null when no path of that kind was recorded.
std::shared_ptr<const LegTrajectory> trajectory_subset(const LegTrajectory& leg, bool stuck);

/// Where a robot that gets through is, when the NOISE is redrawn within the
/// state: the held paths that got through, and the stuck ones with their
/// weights times `escaped`, the share of their robots a redraw frees (a run
/// whose first draw pins it stays on that path's way until a redraw lets it
/// go), renormalised. `escaped` 0 is trajectory_subset(leg, false). Null when
/// nothing is left.
std::shared_ptr<const LegTrajectory> trajectory_getting_through(const LegTrajectory& leg, double escaped);

/// Splits τ (seconds since the state's entry) into at most `max_bins` bins of
/// equal probability (one when the robot hardly moves over τ's spread) and
/// places the robot in each. Bins' probabilities sum to 1. Empty when the
/// trajectory or τ is empty.
std::vector<InterruptionBin> interruption_bins(const LegTrajectory& leg, const Mixture1& tau_s, std::size_t max_bins);

/// The moments of X restricted to (lo, hi]: its probability there, and the
/// conditional mean and variance (exact, per component: truncated normals;
/// point masses count where they lie).
void truncated_moments(const Mixture1& x, double lo, double hi, double& probability, double& mean, double& var);

/// The p-quantile of a mixture (bisection on its CDF).
double mixture_quantile(const Mixture1& x, double p);

}  // namespace p3at::verifier::engine
