#pragma once
/// One robot in one FSA state: the tail-recursive subsystem "state network |
/// robot model | environment" iterated cycle by cycle (its period process
/// Sys' is one control cycle; the flow function is the executive's own motor
/// schemas feeding the robot model) until the state's abort condition Ω (its
/// self-timed triggers) holds. NOISE's uniformly random direction is the only
/// random input of that flow, so it is integrated by deterministic quadrature
/// over equally spaced directions (sigma points); each direction's path is
/// exact under the model. Message-driven exits are left to the sequencer.

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "engine/error_mixture.hpp"
#include "engine/error_state.hpp"
#include "engine/leg_trajectory.hpp"
#include "engine/sonar_model.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/mog.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier::engine {

/// A transition the state ends by on its own (AtGoal, HasTurned, MessageSent),
/// with the probability it is the one that fires and the state's duration
/// (seconds from entry) when it does.
struct TimedExit {
  std::size_t transition = 0;   ///< index into RobotSpec::transitions
  double probability = 0.0;
  Mixture1 duration_s;
};

/// One of equally likely points of where the previous state left the robot:
/// its odometric pose and velocities, and the part of the true pose's error
/// that this pose explains (error_given_end's regression within turn groups),
/// which the next state's own steering undoes (a path that ended turned 5
/// degrees more turns 5 degrees less next). The rest of the error, common to
/// every point, is the ErrorState the state is entered with.
///
/// Why points rather than the mean pose: where a leg starts decides which way
/// the robot turns to face its goal (a robot arriving at a patrol's end turns
/// left or right to go back; with a rotation-scale error the two groups end
/// with lateral errors of opposite sign), and whether a wall's avoidance field
/// pins it. Started from the mean every path turns the same way.
struct StartPoint {
  BaseState q;
  Eigen::Vector3d error_offset = Eigen::Vector3d::Zero();
};

/// A mean odometric position sample along the state's path, and the spread
/// of the NOISE paths' positions about it at that moment (how far along the
/// leg they have got differs from path to path).
struct PathSample {
  double offset_s = 0.0;
  double x_m = 0.0, y_m = 0.0;
  double var_xx = 0.0, var_xy = 0.0, var_yy = 0.0;
};

struct StateAnalysis {
  std::vector<TimedExit> exits;       ///< probabilities sum to 1 - blocked
  double blocked = 0.0;               ///< probability no self-timed exit ever fires (stuck, or none exists)
  /// Mean odometric position where the stuck paths ended (for reporting where
  /// a robot is blocked; the start when none moved or blocked == 0).
  double blocked_x_m = 0.0, blocked_y_m = 0.0;
  BaseState end;                      ///< mean odometric pose and velocities when the state ends
  Eigen::Matrix2d end_spread = Eigen::Matrix2d::Zero();  ///< odometric end-position spread (GoToGuarded)
  bool sets_spread = false;           ///< true when end_spread replaces the robot's previous spread
  /// Each finished NOISE path's true end (its odometric end plus its error's
  /// deviation from the mean error) minus their mean (equally likely unless end_weights says otherwise;
  /// end_spread is the odometric ends' covariance). The end points lie near the AtGoal circle,
  /// so the distance to the goal hardly varies over them: kept as points, the
  /// final position is a mixture that keeps that, where one Gaussian would
  /// smear the arc into a spread of the distance that is not there.
  std::vector<Eigen::Vector2d> end_offsets;
  /// Each end_offsets point's probability when they differ (one point per
  /// path of a leg without NOISE entered from unequal start points); empty
  /// when the points are equally likely.
  std::vector<double> end_weights;
  /// The true ends' spread that end_offsets do not show (a redrawn NOISE's
  /// many paths are averaged into `directions` slabs).
  Eigen::Matrix2d end_offsets_within = Eigen::Matrix2d::Zero();
  /// How much later than the points' mean each end_offsets point's paths
  /// fired (seconds; the same order): a path pushed toward the goal arrives
  /// early and ends nearer it, so the completion time and the final position
  /// are correlated through them (RobotOutcome::final_time_scores).
  std::vector<double> end_delays;
  /// The same paths' true positions once each has braked to rest on its own
  /// (from its speed and heading at the firing), relative to where the mean
  /// end (`end`) comes to rest, and what they average away: filled when an
  /// exit leads to a state that stops the robot (the sequencer uses them on
  /// entering one), empty otherwise.
  std::vector<Eigen::Vector2d> rest_offsets;
  std::vector<double> rest_weights;   ///< end_weights for rest_offsets
  Eigen::Matrix2d rest_offsets_within = Eigen::Matrix2d::Zero();
  std::vector<double> rest_delays;    ///< end_delays for rest_offsets
  ErrorState error;                   ///< the true pose's error at the end
  /// The paths' own errors at the end (their residuals after the regression
  /// above), kept apart as a mixture (engine/error_mixture.hpp); `error.cov`
  /// includes their spread. Empty for states that do not move.
  ErrorMixture error_paths;
  /// Where the state left the robot, as equally likely points (StartPoint),
  /// for the next state's entry; empty for a state that never ends by itself.
  std::vector<StartPoint> end_points;
  std::vector<PathSample> path;       ///< every second, for separation (safety) criteria
  std::size_t cycles_simulated = 0;   ///< work done, for budgets and benchmarks
  /// Pose versus time per NOISE path, for a motion state a message can
  /// interrupt (one with a Notified exit); null otherwise (engine/interruption).
  std::shared_ptr<const LegTrajectory> trajectory;
  /// The same for the paths that got stuck (pinned, or held off the goal):
  /// where a robot on one of them waits for the message; null when none did.
  /// `trajectory` then holds only the paths that got through.
  std::shared_ptr<const LegTrajectory> stuck_trajectory;
};

class MovingBodies;  // engine/moving_bodies.hpp

/// What a state's evaluation needs to know about the rest of the system.
struct StateContext {
  const mission::RobotSpec* robot = nullptr;
  const RobotModel* model = nullptr;
  const Models* models = nullptr;
  std::vector<Segment> obstacles;     ///< walls plus the bodies of teammates that hold still
  /// The walls alone among `obstacles`: what the robot's body stalls against
  /// (body_contact.hpp). Not the teammates' bodies: the model puts a parked
  /// teammate where it would park alone, blind to this robot in its way, and
  /// a stall against that body is all or nothing where runs jostle (gen_7486:
  /// 0.149 of a robot's mass stuck against a parked teammate, no run stuck).
  std::vector<Segment> walls;
  /// Teammates driving a leg, as bodies that move with the state's cycles
  /// (engine/moving_bodies.hpp); null when none comes near.
  std::shared_ptr<const MovingBodies> movers;
};

/// Evaluates state `state_index` of the robot, entered with odometric base
/// `start` and error `error_start`.
StateAnalysis analyze_state(const StateContext& context, std::size_t state_index, const BaseState& start,
                            const ErrorState& error_start, const std::vector<StartPoint>& start_points = {});

/// At most this many start points are carried from one state to the next
/// (StateAnalysis::end_points), and at most kStartPointsEntered of them,
/// merged in the order that matters to the state entered (which way the
/// robot turns to its goal), start its paths.
inline constexpr std::size_t kStartPointsCarried = 8;
inline constexpr std::size_t kStartPointsEntered = 4;

/// `n` equally likely points standing for weighted points, in the order of
/// `key` (ascending): slabs of equal probability of the sorted points, each
/// the average of what falls in it. Headings are averaged as given: the
/// caller keeps them continuous (within pi of their mean). The points'
/// weighted mean is kept.
std::vector<StartPoint> equal_weight_points(const std::vector<StartPoint>& points, const std::vector<double>& weights,
                                            const std::vector<double>& key, std::size_t n);

/// Whether entering `state` stops the robot until it is at rest (a final
/// state, a still one that is not timed by an acknowledgement, a Spin whose
/// turn outlasts braking from top speed, or an acknowledgement-timed one
/// whose acknowledgement leads only to such states), so that
/// the previous leg's paths each run out their own braking
/// (StateAnalysis::rest_offsets).
bool brakes_to_rest(const mission::RobotSpec& robot, std::size_t state, const Kinematics& kin);

/// Final state `state_index` of the robot, entered with odometric base `start`
/// (its velocities those at the firing) and error `error_start`: the executive
/// stops the base on entering a final state, whatever its behaviour, so the
/// robot runs out its braking as in a Stop. `end` is where the base comes to
/// rest and `error` the error propagated over the run-out (no exits).
StateAnalysis analyze_final(const StateContext& context, std::size_t state_index, const BaseState& start,
                            const ErrorState& error_start);

/// A delay (seconds) seen through the executive's cycle: the number of whole
/// cycles until it has elapsed (at least one), as a mixture over cycle counts.
Mixture1 delay_in_cycles(const Mixture1& delay_s, double cycle_s, std::size_t max_components);

}  // namespace p3at::verifier::engine
