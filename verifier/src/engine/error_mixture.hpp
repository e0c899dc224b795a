#pragma once
/// The part of a robot's true-pose error e = r - q that differs between NOISE
/// paths, kept as a small Gaussian mixture instead of folded into one
/// covariance.
///
/// Why: a robot that turns around at the start of a leg turns left on some
/// NOISE paths and right on others; with a rotation-scale error (k - 1) the
/// two groups end with heading errors of opposite sign, and the rest of the
/// mission carries them as lateral errors of opposite sign (a U-turn and 7 m
/// at k = 1.02: about +-0.44 m). One Gaussian puts most of that mass near
/// zero error, so the robot is predicted closer to its goal than any run ends
/// (generated gen_1166: 0.28 m where 4,000 runs end 0.48 m away).
///
/// Representation: components (w_k, delta_k, C_k) with sum w_k = 1, relative
/// to ErrorState::mean. ErrorState::cov stays the TOTAL covariance (every
/// other user of the error, e.g. separations, reads it as before); the part
/// no component explains, cov - sum w_k (C_k + delta_k delta_k^T), is common
/// to all components (the within-path random error). Empty = one component
/// at the mean with C = 0 (nothing kept apart).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace p3at::verifier::engine {

struct ErrorComponent {
  double weight = 1.0;
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();  ///< (ex_m, ey_m, etheta_rad) minus the error's mean
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();    ///< this component's own spread (from merges)
};

using ErrorMixture = std::vector<ErrorComponent>;

/// At most this many components are carried (merged pairwise beyond it).
inline constexpr std::size_t kMaxErrorComponents = 4;

/// The mixture after a state whose odometric displacement was (dx, dy): a
/// heading error at the state's entry turns the whole odometric path about
/// the true start, moving the end by e_theta * (-dy, dx).
void transport(ErrorMixture& m, double dx_m, double dy_m);

/// Two independent mixtures added (every pair of components), reduced to
/// `max_components`.
ErrorMixture convolve(const ErrorMixture& a, const ErrorMixture& b, std::size_t max_components);

/// Two branches' mixtures weighted by the branches' weights, each relative to
/// its own error mean, re-centred on the merged mean (wa ma + wb mb) / (wa + wb).
ErrorMixture blend_branches(const ErrorMixture& a, const Eigen::Vector3d& mean_a, double wa, const ErrorMixture& b,
                            const Eigen::Vector3d& mean_b, double wb, std::size_t max_components);

/// Merges the closest pair (weighted squared distance, a heading error
/// counted as the lateral error it makes over 5 m) until at most
/// `max_components` remain; each merge keeps the pair's weight, mean and
/// covariance (moment matching). Also re-centres the deltas on zero.
void reduce(ErrorMixture& m, std::size_t max_components);

/// The mixture's position deltas turned (and shortened, never lengthened)
/// onto the main axis of `total`, the error's whole covariance, when the
/// spread between the components is most of it. The two describe one spread
/// by different approximations (the total propagated cycle by cycle along the
/// paths, the components moved along each state's straight displacement), and
/// a few degrees between their axes leave, in total minus what the
/// components explain, a residual of the spread's length times the angle
/// that would widen every component: on the fresh sweep's gen_5157 robot1
/// (12 % of runs 0.45 m off the rest, after a leg that some runs leave
/// turning the other way) 3.4 degrees made every component 6 cm wide, where
/// the runs' main group is 2.5 cm wide.
ErrorMixture aligned_to_total(const ErrorMixture& m, const Eigen::Matrix2d& total);
/// sum w_k (C_k + delta_k delta_k^T): the covariance the components explain.
Eigen::Matrix3d explained_cov(const ErrorMixture& m);

/// A covariance difference made a covariance again: symmetrised, negative
/// eigenvalues (rounding, linearisation) floored at zero. For what is common
/// to every component (the total less what the components explain) and for
/// what a set of end points does not show.
Eigen::Matrix2d floored_psd(Eigen::Matrix2d m);

}  // namespace p3at::verifier::engine
