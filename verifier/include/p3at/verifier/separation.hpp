#pragma once
/// Separation (safety) probabilities, the paper's eq. (6) read as "at all
/// times": P(for every t, |p(t) - q(t)| > d), from a branch's separation
/// samples (outcome.hpp; each robot's predicted position at the same mission
/// times, engine/separations.hpp). docs/verifier.md, "Separation criteria".
///
/// How: within a stretch of at most kSeparationWindowS seconds the pair's
/// relative position is taken as its mean path plus ONE Gaussian error,
/// D(t) = m(t) + L(t) z with z ~ N(0, I) common to the stretch (L(t) L(t)^T
/// the sample's covariance, interpolated along the segments between samples):
/// over a few seconds the robots' errors (how far along their legs they are,
/// how far off their lanes) hardly change. P(the pair comes within d in the
/// stretch) is then the mass of the z for which the path m + L z passes
/// within d of 0, by quadrature over a grid of z. Stretches are combined by
/// Boole's inequality (P(close somewhere) <= the sum), which needs no
/// assumption about how the errors of stretches far apart are related: a
/// lower bound on P(always apart). The mass outside the grid counts as close.

#include <cstddef>
#include <vector>

#include "p3at/verifier/outcome.hpp"

namespace p3at::verifier {

/// The longest stretch of samples taken as one common error (seconds).
inline constexpr double kSeparationWindowS = 20.0;

/// The distance a separation is decided at, as the gate decides Rmax
/// (verify.hpp, decision_point()): "never within d" (apart = true) at d 1 %
/// larger and at least step_m larger; "always within d" as much smaller
/// (never below 0). Why: a distance that is deterministic (two robots that
/// start 1 m apart) puts a step in the curve, and the model's millimetres
/// decide which side of it d falls (Bounding Overwatch's runs all come within
/// 1.000 m: their start; verify said 0.93 at d = 1.0).
double decided_separation(double d_m, bool apart, double step_m);

/// P(robots i and j are never within d_m of each other) in branch b: a lower
/// bound (Boole over stretches). 0 when d_m is beyond half of
/// kSeparationHorizonM (the samples do not cover it: cannot be vouched for).
double probability_always_apart(const Branch& b, std::size_t i, std::size_t j, double d_m);

/// P(robots i and j are within d_m of each other at every sample) in branch
/// b: a lower bound (Fréchet over stretches); 0 when the pair ever parts
/// beyond the horizon, or d_m is beyond half of it.
double probability_always_within(const Branch& b, std::size_t i, std::size_t j, double d_m);

/// At most this much of an outcome's branch mass (its lightest branches) is
/// counted as failure by probability_no_pair_within without being asked.
inline constexpr double kNegligibleBranchMass = 1e-6;

/// P(no two robots of the team are ever within d_m of each other), over the
/// outcome's branches by weight: a lower bound (Boole over pairs too); the
/// mass the evaluation did not finish (pruned, blocked, cut off) counts as
/// failure, and so do the lightest branches up to kNegligibleBranchMass. The cross-check's closest-approach curve (validation measures
/// each run's smallest distance between any two robots).
double probability_no_pair_within(const SystemOutcome& outcome, double d_m);

/// The same at each of ds, in one pass over the branches: each pair's
/// stretches are cut once for all of them, and a branch stops being asked
/// at a d once it counts nothing there. Equal, number for number, to asking
/// each d alone. Why: the cross-check asks a curve of d (and the distance
/// each point is decided at), and gen_7610's 23,060 branches took over an
/// hour asked one d at a time.
std::vector<double> probability_no_pair_within(const SystemOutcome& outcome, const std::vector<double>& ds);

}  // namespace p3at::verifier
