#pragma once
/// The closest-approach curve (issue 13 item 8): P(no two robots are ever
/// within d of each other) over an axis of d, verify's lower bound
/// (p3at/verifier/separation.hpp, the separation criterion's computation)
/// against the fraction of runs whose closest approach (the smallest true
/// centre distance between any two robots at any cycle) is above d. Scored
/// like the radius curve (strict and with the 1 % shift), with the points
/// where verify says at least 0.8 while the runs' whole 95 % interval is
/// below 0.78 counted as over-confident. docs/crosscheck.md.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "p3at/crosscheck/scoring.hpp"
#include "p3at/team_sim/run_result.hpp"
#include "p3at/verifier/outcome.hpp"

namespace p3at::crosscheck {

struct SeparationScore {
  std::string range;                    ///< the d axis, A:B:STEP (metres)
  ErrorSummary error;                   ///< its "rmax_m" fields are d
  std::size_t overconfident_points = 0;
};

/// nullopt for a one-robot mission, and when no run's robots came within
/// the distance the verifier can vouch for (half of kSeparationHorizonM).
/// The errors are the raw curve's; the over-confident points are counted on
/// what the gate decides at each d (verifier::decided_separation() with
/// `step_m`, the step verify decides separations with), as for the joint
/// surface's cells.
std::optional<SeparationScore> score_separation(const verifier::SystemOutcome& outcome,
                                                const std::vector<team_sim::RunResult>& runs, std::size_t points,
                                                double step_m);

}  // namespace p3at::crosscheck
