#pragma once
/// The pace of a recorded leg under a redrawn NOISE (engine/leg_trajectory.hpp).
///
/// A state a message can interrupt records each NOISE direction's pose versus
/// time; under a redrawn NOISE those are the held quadrature's paths (one
/// direction for the whole state), the only ones that keep a path's identity.
/// A held direction is a steady push, which the robot's heading settles
/// against; a NOISE redrawn every few cycles keeps turning it, and the robot
/// makes less way along its leg in the same time. The redrawn quadrature's
/// mean path (NoiseQuadrature::mean_path, a position per second) has that
/// pace: each of its seconds is matched to the time at which the held paths'
/// mean is nearest to it (never going back), and the paths are read at that
/// time; and their offsets around their mean are brought to the redrawn
/// quadrature's spread at that second (the held directions, each pushing
/// its path aside for the whole state, fan out far wider). gen_7038's robot3
/// (NOISE gain 0.255 redrawn every cycle, recalled about 10.3 s into an 8 m
/// leg): the held paths' mean was 0.10 m farther along at 10 s than the
/// redrawn mean path, which is where the runs are, and their spread three
/// times the runs': its final distance 5.187 +- 0.288 m before, 5.284 +-
/// 0.098 m now, 400 runs 5.288 +- 0.088 m (verifier_test_final_distance_cli).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "engine/leg_trajectory.hpp"
#include "engine/state_analysis.hpp"

namespace p3at::verifier::engine {

/// The time on `held`'s paths for each whole second of the state's time (the
/// samples of `redrawn_mean`, whose offsets are 0, 1, 2, ... s); empty when
/// there is nothing to match.
std::vector<double> path_times_at_pace(const LegTrajectory& held, const std::vector<PathSample>& redrawn_mean);

/// The redrawn quadrature's spread of positions at the same seconds
/// (LegTrajectory::redrawn_cov_m2): `redrawn_mean`'s variances, as many as
/// path_times_at_pace matched.
std::vector<Eigen::Matrix2d> redrawn_spreads(const std::vector<PathSample>& redrawn_mean, std::size_t seconds);

/// Offsets of the held paths around their mean (their weighted covariance
/// `held_cov`) brought to the spread `target` by the symmetric map
/// target^(1/2) held_cov^(-1/2): the same shape of points, the redrawn
/// spread. Offsets that hardly spread at all (below 1 mm) are left alone.
std::vector<Eigen::Vector2d> offsets_at_spread(const std::vector<Eigen::Vector2d>& offsets,
                                               const Eigen::Matrix2d& held_cov, const Eigen::Matrix2d& target);

}  // namespace p3at::verifier::engine
