#pragma once

#include <optional>

#include <Eigen/Core>

namespace p3at::verifier::engine {

/// A state's analysis (its paths, its end) is made once, from where the
/// robot entered the state. When branches in which the robot entered the
/// same state from different places merge, one analysis goes on for all of
/// them, and the merged start (their weighted mean) is `moved` away from the
/// analysis's start. A point of the analysis moves with it by the share of
/// the leg still ahead of it: a leg to a goal forgets where it began as it
/// gets there (straight to the goal, the point a fraction f of the way along
/// moves by (1 - f) of the start's move), and a state without a goal (a
/// Stop, a Notify, a Spin) moves entirely.
///
/// `analysis_start` is where the analysis began, `goal` the leg's goal
/// (none for a state without one). Returns the share 1 - f, in [0, 1].
double share_still_ahead(const Eigen::Vector2d& analysis_start, const std::optional<Eigen::Vector2d>& goal,
                         const Eigen::Vector2d& point);

/// Whether two branches' places of one robot (mean and covariance of its
/// position in each) may merge into one Gaussian place: apart by at most
/// twice the sum of their spreads along the line between them, plus 2 cm.
/// Farther apart, the merged place would be one wide Gaussian where the
/// robot is in one of two narrow ones (gen_7056: 0.04 % of the mass at a
/// leg's goal 10 m from where the rest was recalled made robot1's final
/// distance 0.205 m wide where the runs' is 0.072 m): the branches stay
/// apart.
bool close_enough_to_merge(const Eigen::Vector2d& mean_a, const Eigen::Matrix2d& cov_a, const Eigen::Vector2d& mean_b,
                           const Eigen::Matrix2d& cov_b);

}  // namespace p3at::verifier::engine
