#pragma once
/// What the system evaluation (the sequence of tail-recursive subsystems,
/// Def. 10) produces: the distribution of the final state, as weighted
/// branches (orderings of the robots' abort conditions), each with per-robot
/// random variables. Criteria (criteria.hpp) are evaluated on this.

#include <cstddef>
#include <string>
#include <vector>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {

/// One robot in one branch at the end of the mission.
struct RobotOutcome {
  /// When its FSA reached a final state (mission clock, seconds from launch).
  Mixture1 finish_time_s;
  /// Its true final position (moment-matched when final_components is not empty).
  Gaussian2 final_position;
  /// The true final position as a mixture, when the robot's last GoToGuarded
  /// left one end point per NOISE direction or its error differs between
  /// NOISE paths (empty: use final_position). Radius criteria use it: the end
  /// points lie on an arc of the AtGoal circle, and a robot that turned
  /// around one way or the other ends on one side or the other, which one
  /// Gaussian cannot represent.
  std::vector<Gaussian2> final_components;
  /// The components' weights (summing to 1); empty: equal weights.
  std::vector<double> final_weights;
  /// Which of the last leg's NOISE paths each final component comes from,
  /// as a score for when they fired: standardised (mean 0, variance 1 over
  /// the components) so that a path that arrived late scores high. Empty
  /// when not known. With time_score_correlation, the finish time given a
  /// component (engine/time_position.hpp): a path pushed toward its goal
  /// arrives early and runs out closer to it, so within a branch the time
  /// and the position are not independent (issue 13 item 7).
  std::vector<double> final_time_scores;
  /// The correlation of finish_time_s with the score, in [0, 0.95].
  double time_score_correlation = 0.0;
  /// Where its odometry says it is at the end (the mean the executive believes).
  Eigen::Vector2d believed_position = Eigen::Vector2d::Zero();
  /// The names of the FSA states it went through, in order (its trace).
  std::vector<std::string> states;
  bool finished = true;   ///< false if it never reached a final state in this branch (blocked, looped)
};

/// Weight of final component k.
inline double component_weight(const RobotOutcome& r, std::size_t k) {
  return r.final_weights.size() == r.final_components.size() ? r.final_weights[k]
                                                              : 1.0 / static_cast<double>(r.final_components.size());
}

/// P(|final position - centre| < radius): over final_components when there
/// are any, else with final_position.
inline double final_within(const RobotOutcome& r, const Eigen::Vector2d& centre, double radius) {
  if (r.final_components.empty()) return probability_within(r.final_position, centre, radius);
  double sum = 0.0;
  for (std::size_t k = 0; k < r.final_components.size(); ++k) sum += component_weight(r, k) * probability_within(r.final_components[k], centre, radius);
  return sum;
}

/// A sample of two robots' relative true position at some moment, for safety
/// criteria (eq. 6): difference = position(i) - position(j), both at the same
/// mission time (each robot's predicted position then, engine/separations.hpp).
struct SeparationSample {
  std::size_t robot_i = 0;
  std::size_t robot_j = 0;
  double time_s = 0.0;          ///< mean mission time of the sample
  Gaussian2 difference;
  /// The pair's previous sample (in the branch's list) is the moment just
  /// before this one: between the two the difference moves along the segment
  /// joining them. False for a pair's first sample and after a gap (samples
  /// whose mean distance was beyond the horizon are not kept).
  bool joined = false;
  /// The pair's first sample beyond kSeparationHorizonM, kept (the others
  /// are not) so that a criterion about robots staying together sees that
  /// they parted; a criterion about robots coming close ignores it.
  bool beyond_horizon = false;
  /// For how long around this moment the pair's error can be taken as one
  /// fixed draw (p3at/verifier/separation.hpp): the shorter of the two
  /// robots' (a NOISE redrawn every k cycles moves a robot off its mean path
  /// afresh every k cycles; held for the whole leg, or absent, the error
  /// changes only as the odometry's drift grows).
  double rigid_s = 0.0;
};

/// Separation samples whose mean distance is beyond this are not kept: they
/// cannot matter to a criterion about robots coming within half of it.
inline constexpr double kSeparationHorizonM = 6.0;

/// One ordering hypothesis of the robots' abort conditions.
struct Branch {
  double weight = 1.0;
  std::vector<RobotOutcome> robots;          ///< indexed like Mission::robots
  Mixture1 completion_time_s;                ///< when the last robot finished
  std::vector<SeparationSample> separations; ///< along the branch
  /// ordering[k] = index of the robot whose abort condition fired k-th, for
  /// ordering criteria (t_i < t_j).
  std::vector<std::size_t> event_robots;
};

/// Facts the evaluation noticed about where its own model is approximate,
/// for the approximations check (approximations.hpp). Deduplicated: one
/// record per distinct situation, whatever the number of branches.
///
/// A robot that cannot finish in some branch: which one, in which state,
/// where (mean true position), and why ("stuck" on its path, "waiting" for a
/// message nobody will send, "stuck-waiting": stuck on its path in a state a
/// message would have taken it out of, "loop" past Budget::max_events).
struct BlockedRecord {
  std::size_t robot = 0;
  std::size_t state = 0;
  double x_m = 0.0, y_m = 0.0;
  std::string why;
  double mass = 0.0;   ///< probability of this situation (summed over branches)
};
/// An event where three or more robots could each plausibly fire first: the
/// order is then a product of pairwise probabilities (an approximation).
struct RaceRecord {
  std::vector<std::size_t> robots;
  std::vector<std::size_t> states;  ///< each robot's state, same order
};
/// Robot `robot` entered GoToGuarded state `state` while `teammate` was
/// driving its own GoToGuarded leg `teammate_state`: the evaluation of each
/// leg ignores the other (it is not an obstacle), and teammates holding
/// still are frozen where they stood at the state's start. Legs as segments
/// from the mean position at entry to the goal.
struct ConcurrentLegs {
  std::size_t robot = 0, state = 0;
  std::size_t teammate = 0, teammate_state = 0;
  double x0_m = 0.0, y0_m = 0.0, x1_m = 0.0, y1_m = 0.0;     ///< robot's leg
  double tx0_m = 0.0, ty0_m = 0.0, tx1_m = 0.0, ty1_m = 0.0; ///< teammate's leg (from where it is now)
};

/// To keep within Budget::max_branches, branches that differed only in where
/// robot `robot` was (the bins of a message interrupting it; in `state` when
/// merged) were merged into one place (approximations.hpp,
/// `places-merged-over-budget`). One record per (robot, state).
struct BudgetMerge {
  std::size_t robot = 0, state = 0;
  bool branch_budget = false;  ///< its places merged into fewer (Budget::max_branches)
  bool work_budget = false;    ///< a leg took a nearby place's analysis (past half of max_work_cycles)
};

/// Robot `robot` entered GoToGuarded state `state` from odometry position
/// (x0_m, y0_m) with this predicted pose error (true minus odometry: x, y,
/// heading; its mean and covariance). The model steps its paths at the mean
/// error; the trap check also tries the leg moved into the error's tails
/// (approximations.cpp, traps()), where a run may meet a gap or a corner the
/// mean path misses. A few per state.
struct LegEntryRecord {
  std::size_t robot = 0, state = 0;
  double x0_m = 0.0, y0_m = 0.0;
  Eigen::Vector3d error_mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d error_cov = Eigen::Matrix3d::Zero();
};

struct SystemOutcome {
  std::vector<Branch> branches;   ///< weights sum to 1 - pruned_mass - blocked_mass
  double pruned_mass = 0.0;       ///< ordering mass dropped to keep within Budget::max_branches
  /// The finished branches' mass whose places were merged to keep within
  /// Budget::max_branches (BudgetMerge): not lost, pictured more coarsely.
  double budget_merged_mass = 0.0;
  double blocked_mass = 0.0;      ///< mass of branches where some robot can never finish (deadlock)
  /// Mass of the laps of an FSA loop beyond the budget (a robot entering the
  /// same state more than Budget::max_events / 100 times, at least once, in one
  /// branch): the tail-recursion unrolled lap by lap, the rest counted as failure.
  double loop_cutoff_mass = 0.0;
  /// Mass of the branches still unevaluated when Budget::max_work_cycles ran
  /// out, counted as failure.
  double work_cutoff_mass = 0.0;
  /// Past half of Budget::max_work_cycles, a state entered from a place it had
  /// no analysis for took the nearest place's (Sequencer::cached_analysis);
  /// recorded in budget_merges and budget_merged_mass like the branch budget's merges.
  bool work_pressure_merged = false;
  std::size_t work_cycles = 0;    ///< robot control cycles the within-state models simulated
  std::size_t subsystems = 0;     ///< TR subsystems evaluated (Def. 10 steps), summed over branches
  std::size_t ordering_splits = 0;  ///< events where more than one robot could plausibly fire first
  std::vector<BlockedRecord> blocked;          ///< who blocked_mass belongs to
  std::vector<RaceRecord> races;               ///< events with three or more plausible first robots
  std::vector<ConcurrentLegs> concurrent_legs; ///< pairs of legs driven at the same time
  std::vector<LegEntryRecord> leg_entries;     ///< odometry errors at GoToGuarded entries
  std::vector<BudgetMerge> budget_merges;      ///< robots whose places were merged over the budget
};

}  // namespace p3at::verifier
