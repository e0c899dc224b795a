#pragma once
/// A motion state's pose as a function of time, per NOISE quadrature path:
/// what a message interrupting the state (a Notified transition out of a
/// GoToGuarded or a Spin: a robot recalled mid-leg, a patrol left mid-beat)
/// needs to know to put the robot where the interruption finds it. Recorded
/// by the state analysis only for states that a message can interrupt.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "engine/error_state.hpp"

namespace p3at::verifier::engine {

/// The odometric pose (with the base's velocities) and the true pose's error
/// after a whole number of cycles in the state.
struct TrajectoryPoint {
  BaseState base;
  ErrorState error;
};

struct LegTrajectory {
  double cycle_s = 0.1;
  /// paths[j][n]: quadrature path j after n cycles; n = 0 is
  /// the entry. A path's list ends at the cycle its own exit fired (or at the
  /// state's cycle cap): a later time finds the robot where the list ends.
  std::vector<std::vector<TrajectoryPoint>> paths;
  /// paths[j]'s probability (they sum to 1; equal when empty).
  std::vector<double> weights;
  /// stuck[j]: no self-timed exit ever fired on path j (it reached the
  /// state's cycle cap, or stood still for good: noise_segments.cpp).
  std::vector<char> stuck;
  bool is_stuck(std::size_t j) const { return j < stuck.size() && stuck[j] != 0; }
  double weight(std::size_t j) const {
    return j < weights.size() ? weights[j] : 1.0 / static_cast<double>(paths.empty() ? 1 : paths.size());
  }
  /// Under a redrawn NOISE the paths are the held quadrature's (one direction
  /// each for the whole state), which run ahead of the redrawn robot: the
  /// time on the paths at each whole second of the state's time, so that
  /// their mean keeps the redrawn quadrature's pace (engine/trajectory_pace.hpp).
  /// Empty: the paths' own time.
  std::vector<double> path_time_s;
  /// The time on the paths for `t_s` seconds in the state.
  double path_time(double t_s) const;
  /// With `path_time_s`: the redrawn quadrature's spread of positions
  /// (odometric, m^2) at each whole second of the state's time. A held
  /// direction pushes its path aside for the whole state and the held paths
  /// fan out far wider than a robot whose NOISE keeps turning: an
  /// interruption's places are the held paths' offsets brought to this
  /// spread (interruption_bins). Not carried into a subset of the paths
  /// (trajectory_subset, trajectory_getting_through): the redrawn spread is
  /// that of every path together.
  std::vector<Eigen::Matrix2d> redrawn_cov_m2;
  /// That spread after `t_s` seconds in the state (interpolated; the last
  /// second's beyond it). Requires a non-empty `redrawn_cov_m2`.
  Eigen::Matrix2d redrawn_cov(double t_s) const;
};

}  // namespace p3at::verifier::engine
