#pragma once
/// Random variables as mixtures of Gaussians (the seed paper's representation).
/// One-dimensional mixtures for times and delays; two-dimensional Gaussians for
/// positions. Every operation is deterministic (no sampling): the same inputs
/// give bit-identical outputs.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace p3at::verifier {

/// One weighted 1-D component.
struct Component1 {
  double weight = 1.0;
  double mean = 0.0;
  double var = 0.0;   ///< >= 0; 0 is a point mass
  bool operator==(const Component1&) const = default;
};

/// A 1-D mixture. Weights are kept normalised by every operation that
/// produces a mixture (an empty mixture is "no distribution").
/// Conventions shared by the operations below: a max_components of 0 means 1;
/// an empty input gives an empty result (and probabilities of 0); results are
/// sorted by increasing mean (ties by variance, then weight).
struct Mixture1 {
  std::vector<Component1> components;

  static Mixture1 point(double value);
  static Mixture1 gaussian(double mean, double var);

  /// NaN for an empty mixture (or one without weight).
  double mean() const;
  double variance() const;
  /// P(X <= x). A point mass at x counts as <= x. 0 for an empty mixture.
  double cdf(double x) const;
  /// Scales the weights to sum to 1 (no-op when empty or all zero).
  void normalise();
  bool operator==(const Mixture1&) const = default;
};

/// X + c.
Mixture1 shifted(const Mixture1& x, double c);
/// X + Y for independent X and Y (pairwise component sums), then reduced to max_components.
Mixture1 sum(const Mixture1& x, const Mixture1& y, std::size_t max_components);
/// max(X, Y) for independent X, Y: Clark's moment-matched Gaussian per pair, then reduced.
Mixture1 maximum(const Mixture1& x, const Mixture1& y, std::size_t max_components);
/// max(X, c) moment-matched per component (Clark with a point mass); one
/// component out per component in, in the same order, not reduced.
Mixture1 maximum(const Mixture1& x, double c);
/// P(X < Y) for independent X, Y: sum over pairs of w_i w_j Phi((m_j - m_i) / sqrt(v_i + v_j)).
/// Two point masses at the same value are not "less" (nor "greater").
double probability_less(const Mixture1& x, const Mixture1& y);
/// The distribution of X given X < Y (X, Y independent), moment-matched per
/// component pair (exact moments of a Gaussian X given the linear constraint
/// X - Y < 0), weighted by w_i w_j P_ij and renormalised, then reduced; the
/// conditioning probability P(X < Y) is returned in `probability`. When the
/// ordering is impossible the result is empty and `probability` 0.
Mixture1 conditioned_less(const Mixture1& x, const Mixture1& y, std::size_t max_components, double& probability);
/// The distribution of X given X > Y, likewise.
Mixture1 conditioned_greater(const Mixture1& x, const Mixture1& y, std::size_t max_components, double& probability);
/// Merges the closest pairs (Runnalls' KL bound, moment-preserving) until at
/// most max_components remain; drops components below 1e-12 weight first.
/// Mean and variance of the whole mixture are preserved exactly by merging.
/// Deterministic whatever the input order: components are sorted first and
/// ties between equally cheap merges go to the lowest indices. A mixture
/// without weight becomes empty.
void reduce(Mixture1& x, std::size_t max_components);
/// A mixture from weighted points (e.g. sigma points) as one moment-matched
/// Gaussian per group of nearby points, at most max_components. Groups are
/// runs of consecutive values (sorted), formed by merging the cheapest
/// neighbours (Runnalls' cost); equal values are one point mass, and with
/// room for every distinct value the result is the points themselves (point
/// masses). The points' weighted mean and variance are kept exactly. Points
/// of weight 0 are ignored; sizes that differ, a negative weight or a value
/// that is not finite throw std::invalid_argument.
Mixture1 from_weighted_points(const std::vector<double>& values, const std::vector<double>& weights,
                              std::size_t max_components);
/// Fits a k-component mixture to samples by expectation-maximisation,
/// deterministically initialised from quantiles. Used by calibration.
/// The samples are sorted first (their order does not matter); components
/// start on k consecutive runs of them; variances are floored at 1e-12 of the
/// samples' variance; iteration stops when the log-likelihood improves by less
/// than 1e-10 of itself, or after max_iterations. k = 0 means 1 and k above
/// the sample count means one per sample; k = 1 is the samples' own mean and
/// variance; identical samples give a point mass; no samples an empty mixture.
/// Samples that are not finite throw std::invalid_argument.
Mixture1 fit_em(const std::vector<double>& samples, std::size_t k, std::size_t max_iterations = 200);

/// A 2-D Gaussian (a position), world frame.
struct Gaussian2 {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
};

/// P(|X - centre| <= radius) for X ~ N(mean, cov), by deterministic quadrature
/// accurate to about 1e-6 (a degenerate covariance is handled as a point or a line).
/// In the covariance's principal axes the major axis is done in closed form
/// (normal CDFs of the disk's chord) and the minor one by adaptive
/// Gauss-Kronrod; a mean more than 10 standard deviations outside (inside)
/// the disk gives 0 (1) at once. A negative radius gives 0.
double probability_within(const Gaussian2& x, const Eigen::Vector2d& centre, double radius);
/// The same, adding to `*intervals` how many quadrature intervals it evaluated
/// (at most 16,384 per call, whatever the covariance: the launch gate's time is bounded).
double probability_within(const Gaussian2& x, const Eigen::Vector2d& centre, double radius, int* intervals);
/// P(|X - Y| > distance) for independent X, Y.
double probability_apart(const Gaussian2& x, const Gaussian2& y, double distance);

/// Standard normal CDF and helpers, exposed for tests and for criteria.
double normal_cdf(double z);
double normal_pdf(double z);
/// The z with normal_cdf(z) = p, to about 1e-12 relative in p; -infinity
/// at p <= 0, +infinity at p >= 1, NaN for NaN.
double normal_quantile(double p);

}  // namespace p3at::verifier
