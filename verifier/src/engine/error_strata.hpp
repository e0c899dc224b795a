#pragma once
/// The pose error a leg is entered with, split into strata where it decides
/// whether the robot meets a wall.
///
/// Why: a path is stepped with the error's MEAN true pose (the sonar sees the
/// walls from it, the body stalls against them there), so whether the robot
/// gets through beside a wall is decided for the mean and given to all of
/// its mass. Where a wall is within reach of the error's tail, the runs in
/// that tail are pinned and the rest are not. Fresh generated missions
/// (seeds 7441-7560): gen_7492's leg4 in a 4.5 m hallway, entered with a
/// sideways error of 0.49 m sd, pins 44 % of 1,000 runs 1.3 m from a side
/// wall, verify blocked 0.1 %; gen_7456's leg4 past a doorway's jamb pins
/// 32 %, verify 0. The model's own paths, started from the mean error moved
/// along the axis below, pin for every shift beyond 0.75 sd (gen_7492) and
/// 0.5-1 sd (gen_7456): the answer is a threshold in that one direction.
///
/// So the entry error is integrated along that axis by a few deterministic
/// strata (slabs of the standard normal, each at its conditional mean, with
/// its probability), each stepped as its own paths; what the slabs leave of
/// the axis's variance stays in every stratum's covariance, so the total
/// error is the same.

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "engine/error_state.hpp"
#include "engine/sonar_model.hpp"
#include "p3at/mission/mission.hpp"

namespace p3at::verifier::engine {

struct Walker;  // engine/path_stepper.hpp

/// One slab of the standard normal along the split axis.
struct ErrorStratum {
  double z = 0.0;       ///< its conditional mean, in sd of the axis
  double weight = 0.0;  ///< its probability
};

/// The slabs: |z| < 0.75, 0.75-1.5, 1.5-2.25 and beyond, on either side.
/// Finer toward the tails than equal slabs, so that a threshold beyond
/// 1 sd (a few percent of the runs pinned) is not all or nothing. Index 0 is
/// the middle.
inline constexpr std::size_t kErrorStrata = 7;
const std::array<ErrorStratum, kErrorStrata>& error_strata();

/// Stratum k's slab of z: [lo, hi] (+-infinity for the outer tails).
struct StratumSlab {
  double lo = 0.0, hi = 0.0;
};
StratumSlab stratum_slab(std::size_t k);

/// The share of the axis's variance the strata carry between them
/// (sum w z^2); the rest is within the slabs.
double strata_variance();

/// The error direction (x, y, heading) that moves the believed leg from
/// `start` to the goal sideways the most, measured as the mean square of the
/// sideways shift over the leg per unit of Mahalanobis length (a heading
/// error turns the leg about its start, so it moves the far end more), scaled
/// to 1 sd of the entry error `error`; or nothing when splitting cannot
/// matter: the error moves the leg by under 2 cm anywhere, or no wall comes
/// within `reach_m` (what AVOID_OBSTACLES and the body can feel) plus 3 sd of
/// that shift of the leg moved by the error's mean.
std::optional<Eigen::Vector3d> wall_sensitive_axis(const BaseState& start, const mission::GoToGuardedParams& go,
                                                   const ErrorState& error, const std::vector<Segment>& walls,
                                                   double reach_m);

class PathStepper;  // engine/path_stepper.hpp

/// Whether the strata can differ in what matters most, getting through:
/// the entries' held-NOISE paths (one draw for the whole state, the cheap
/// quadrature) from the error's mean and from its two outermost strata
/// leave different shares stuck. Where all three get through alike (a long
/// leg down a corridor, the walls within reach but never close) the split
/// would cost its paths for nothing (generated gen_7547: one leg entered at
/// 482 places after a patrol, 28 times the work). `cycles` gets the probes'
/// work (the budget counts it).
bool strata_may_differ(const PathStepper& stepper, const std::vector<Walker>& entries, const Eigen::Vector3d& axis,
                       std::size_t directions, std::size_t cap, std::size_t& cycles);

/// Each walker as kErrorStrata walkers: its error's mean moved by z times
/// `axis` (1 sd of it), its weight times the stratum's probability, its
/// covariance less strata_variance() axis axis^T, and Walker::stratum set.
std::vector<Walker> split_into_strata(const std::vector<Walker>& walkers, const Eigen::Vector3d& axis);

/// The walkers as one stratum at z: each error's mean moved by z times
/// `axis`, its covariance the strata's (less strata_variance() axis axis^T),
/// stratum 0 (engine/stuck_profile's probes).
std::vector<Walker> shifted_along(const std::vector<Walker>& walkers, const Eigen::Vector3d& axis, double z);

}  // namespace p3at::verifier::engine
