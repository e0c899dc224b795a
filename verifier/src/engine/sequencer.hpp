#pragma once
/// The multi-robot mission as a sequence of tail-recursive subsystems (the
/// seed paper's Def. 10): every robot runs its current state's subsystem until
/// the disjunction of their abort conditions holds; the robot whose condition
/// fired moves to its next state; repeat. No interleavings are enumerated:
/// where it is uncertain which robot's condition fires first, each possible
/// order is carried as a weighted branch, branches reaching the same discrete
/// configuration are merged (moment-matched), and the lightest are pruned to
/// Budget::max_branches, the pruned probability mass being reported.
///
/// Times are kept relative to the branch's clock (the last event's time): a
/// robot's pending exit is a residual duration, so the common history of two
/// robots is not counted twice when their exits are compared.

#include "p3at/mission/mission.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/outcome.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::verifier::engine {

/// Evaluates the whole system from the mission's initial states (or from
/// `from`, a snapshot of a mission under way). Preconditions: every mission
/// robot has a model (checked by the caller).
SystemOutcome run_sequence(const mission::Mission& mission, const Models& models, const TeamSnapshot* from);

}  // namespace p3at::verifier::engine
