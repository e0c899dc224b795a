#pragma once
/// The verifier's entry point: the library call behind `vipars verify`,
/// `vipars gate` and the executive's launch gate, all with the same answer.

#include <optional>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/approximations.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/outcome.hpp"

namespace p3at::verifier {

/// A grid cell's class (the paper's three regions), by the joint probability.
enum class Region { unsuccessful, uncertain, successful };
const char* to_string(Region region);  ///< "unsuccessful", "uncertain", "successful"

struct VerifyOptions {
  std::optional<double> tmax_s;      ///< overrides the mission's criteria
  std::optional<double> rmax_m;
  std::optional<double> threshold;
  std::vector<double> tmax_grid;     ///< axis values; both empty = no grid
  std::vector<double> rmax_grid;
  double region_low = 0.05;          ///< p_joint below: high-confidence unsuccessful
  double region_high = 0.95;         ///< p_joint at or above: high-confidence successful
};

/// One extra criterion's verdict (from a --criterion file).
struct CriterionVerdict {
  std::string name;
  double probability = 0.0;          ///< the constraint's probability on the final distribution
  double required = 0.0;            ///< the probability it must reach
  bool holds = false;
  std::string explanation;           ///< human-readable: what was checked
};

struct Grid {
  std::vector<double> tmax;                      ///< axis
  std::vector<double> rmax;                      ///< axis
  std::vector<double> p_time;                    ///< over tmax
  std::vector<double> p_radius;                  ///< over rmax
  std::vector<std::vector<double>> p_joint;      ///< [tmax][rmax]
  std::vector<std::vector<Region>> region;       ///< [tmax][rmax]
};

/// A robot's predicted figures (for logs and reports).
struct RobotPrediction {
  std::string name;
  double finish_mean_s = 0.0, finish_sd_s = 0.0;
  double final_x_m = 0.0, final_y_m = 0.0;       ///< mean true final position
  double final_sd_m = 0.0;                       ///< sqrt(trace(cov)/2)
  double dist_mean_m = 0.0;                      ///< E|true final position - goal| (as vipars validate's)
  double dist_sd_m = 0.0;                        ///< the sd of |true final position - goal| (as vipars validate's)
  double p_radius = 0.0;                         ///< P(r_i <= rmax)
  double p_blocked = 0.0;                        ///< P(it never reaches a final state)
  /// False when no evaluated branch has it finish: the figures above are then
  /// not a prediction (0), and `VerifyResult::blocked` says where it stops.
  bool finishes = true;
};

/// A robot that cannot finish in some branches: which, in which state, where.
struct BlockedRobot {
  std::size_t robot = 0;
  std::string name;
  std::size_t state = 0;
  std::string state_name;
  double x_m = 0.0, y_m = 0.0;   ///< mean true position where it stops
  std::string why;               ///< "stuck" (on its path), "waiting" (for a message nobody sends), "stuck-waiting" (both), "loop"
  double probability = 0.0;
  std::string where;             ///< "file:line:column" of the state (locate_in_mission_file), else empty
};

/// The least the margin may be, whatever 1 % of the criterion is: the
/// model's granularity. Time: one control cycle (durations are whole cycles,
/// and a real run may fire one check later). Radius: the longest step a robot
/// of the mission can make in one cycle (max_speed_mps x cycle_s). Why: the
/// simulator's (and a P3-AT's) odometric error is in what the encoders
/// report, not in where the wheels take the robot, so a run fires its AtGoal
/// at the first check whose *believed* distance is inside the circle, and its
/// true end point is on the lattice of one cycle's steps along its path: a
/// staircase in the distance, within one step of the model's smooth curve
/// (docs/verifier.md, "The decision"). One step stricter reads the model's
/// curve where the staircase cannot be below it.
struct DecisionFloors {
  double time_s = 0.0, radius_m = 0.0;
};

struct VerifyResult {
  double tmax_s = 0.0, rmax_m = 0.0, threshold = 0.0;
  double p_time = 0.0;      ///< P(t <= tmax)
  double p_radius = 0.0;    ///< P(every r_i <= rmax)
  double p_joint = 0.0;     ///< P(t <= tmax and every r_i <= rmax)
  bool go = false;          ///< p_joint >= threshold and every extra criterion holds
  std::vector<std::string> failed;           ///< one line per failed criterion, for refusals
  double completion_mean_s = 0.0, completion_sd_s = 0.0;
  std::vector<RobotPrediction> robots;
  std::optional<Grid> grid;
  std::vector<CriterionVerdict> criteria;
  double pruned_mass = 0.0;
  double budget_merged_mass = 0.0;  ///< SystemOutcome::budget_merged_mass (not lost: merged coarsely)
  double blocked_mass = 0.0;
  double loop_cutoff_mass = 0.0;  ///< SystemOutcome::loop_cutoff_mass
  double work_cutoff_mass = 0.0;  ///< SystemOutcome::work_cutoff_mass (counted as failure)
  std::size_t work_cycles = 0;    ///< SystemOutcome::work_cycles
  std::size_t branches = 0;
  std::size_t subsystems = 0;
  std::vector<BlockedRobot> blocked;          ///< who blocked_mass belongs to
  /// The model's approximations on this mission (approximations.hpp), and
  /// whether every one is vouched for. `go` is the probabilities' decision
  /// alone; decision() combines the two: a GO that is not evaluable is
  /// "cannot evaluate", never GO.
  std::vector<Approximation> approximations;
  bool evaluable = true;
  /// The joint probability at the stricter point the gate decides on
  /// (decision_point()), which `go` is decided on instead of p_joint.
  double p_joint_decided = 0.0;
  double decided_tmax_s = 0.0, decided_rmax_m = 0.0;
  bool widened = false;  ///< an approximation of Treatment::widen made the point stricter still
  DecisionFloors floors;  ///< the least margins the decision took (decision_floors())
};

/// The gate's margin: GO is decided at Tmax (1 - h) and Rmax (1 - h), h = 1 %,
/// never at the criterion itself. Why: a final distance a millimetre off on a
/// radius curve that rises within a centimetre (a robot that creeps into its
/// AtGoal circle ends within millimetres of the same spot every run), or a
/// completion time a cycle off, turns cells next to the curve's rise into
/// wrong GOs, while the prediction is right to within 1 % of the criterion
/// (the cross-check's tolerant scores, docs/crosscheck.md). Deciding 1 %
/// stricter turns those into NO-GO at the cost of 1 % of the operator's margin.
inline constexpr double kDecisionMargin = 0.01;
struct DecisionPoint {
  double tmax_s = 0.0, rmax_m = 0.0;
};
/// The floors of a mission: its models' cycle, its fastest robot's step.
DecisionFloors decision_floors(const mission::Mission& mission, const Models& models);
/// Where the gate decides: 1 % stricter in both but at least the floors
/// stricter, and for an approximation answered by widening also at least
/// kWidenTime_s / kWidenRadius_m stricter.
DecisionPoint decision_point(double tmax_s, double rmax_m, bool widen, const DecisionFloors& floors = {});
/// What the decision point's margin was, for the reports: "1 % stricter, at
/// least one cycle (0.10 s) and one step (0.030 m)" and the widening if any.
std::string decision_margin_text(const VerifyResult& r);

enum class Decision { go, no_go, cannot_evaluate };
/// NO-GO whenever the probabilities say so (a mission predicted to fail is
/// refused whether or not it is evaluable); else GO only if evaluable.
inline Decision decision(const VerifyResult& r) {
  if (!r.go) return Decision::no_go;
  return r.evaluable ? Decision::go : Decision::cannot_evaluate;
}
const char* to_string(Decision d);  ///< "go", "no-go", "cannot-evaluate"

/// Fills the `where` of every approximation and blocked robot from the
/// mission file's text (the bytes the mission was parsed from).
void locate_in_mission_file(VerifyResult& result, std::string_view mission_yaml, const std::string& mission_file);

/// Where the team is now, for re-verification during a mission (the launch
/// gate's in-mission check): the evaluation starts from here instead of from
/// the mission's initial states. Positions are what the robots believe
/// (odometry, world frame); the models add the true-position uncertainty
/// accumulated over `travelled_m` and `turned_rad` so far.
struct RobotSnapshot {
  std::size_t state = 0;            ///< index into RobotSpec::states
  double entered_s = 0.0;           ///< mission time the state was entered
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;  ///< odometric pose
  double travelled_m = 0.0;         ///< odometric distance since launch
  double turned_rad = 0.0;          ///< absolute odometric rotation since launch
  bool finished = false;
};
struct TeamSnapshot {
  double elapsed_s = 0.0;                 ///< mission time now
  std::vector<RobotSnapshot> robots;      ///< indexed like Mission::robots
  std::vector<bool> messages_sent;        ///< indexed like Mission::messages
  std::vector<bool> messages_received;    ///< delivered to every recipient
};

/// Evaluates the system once (mission | robot models | environment) and
/// returns its final distribution. Errors (a mission robot without a model,
/// for instance) come back as Error values naming what is missing.
Result<SystemOutcome> evaluate_system(const mission::Mission& mission, const Models& models,
                                      const TeamSnapshot* from = nullptr);

/// Verifies `mission` against its criteria (overridden by `options`), plus
/// the extra criteria texts in `criteria_files` (PARS criterion files, see
/// docs/verifier.md; parse errors come back with file:line:column).
Result<VerifyResult> verify(const mission::Mission& mission, const Models& models, const VerifyOptions& options,
                            const std::vector<std::string>& criteria_files = {}, const TeamSnapshot* from = nullptr);

/// verify() on an outcome evaluate_system() already gave for this mission and
/// these models: the same result, for callers that read one evaluation on
/// several grids (the cross-check's coarse and fine grids).
Result<VerifyResult> verify_outcome(const mission::Mission& mission, const Models& models, const SystemOutcome& outcome,
                                    const VerifyOptions& options, const std::vector<std::string>& criteria_files = {});

}  // namespace p3at::verifier
