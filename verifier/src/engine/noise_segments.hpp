#pragma once
/// NOISE's direction, integrated segment by segment. The executive draws a
/// uniformly random direction on entering a GoToGuarded state and redraws it
/// every `persistence` cycles; between draws the flow is deterministic. So
/// the state's paths form a branching process: at each redraw every path
/// splits into `directions` equally weighted children (a quadrature of the
/// uniform angle), each driven deterministically to the next redraw, to its
/// trigger or to the cycle cap. The children are then reduced to at most
/// `keep` weighted walkers (`keep_near` where PathStepper::delicate()) (deterministic clustering on pose and velocity,
/// moment-matched, with the pose covariance of the children restored), so
/// the cost is about keep × directions paths whatever the number of redraws.
///
/// With no redraw before the paths end (persistence at least the leg) this
/// is exactly the held-direction quadrature: one path per direction. Under
/// the first draw a path's weight is its arc of the circle: where
/// neighbouring directions of one start end differently, the boundary
/// between them is found by bisection (engine/direction_arcs.hpp).
/// A path that fires during segment s ends there: the duration's
/// distribution is the mass firing at each cycle, and a long tail (a robot
/// held off its goal by a strong NOISE that escapes at some later redraw) is
/// carried as the mass that is still moving, segment after segment.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/direction_arcs.hpp"
#include "engine/error_strata.hpp"
#include "engine/leg_trajectory.hpp"
#include "engine/path_stepper.hpp"

namespace p3at::verifier::engine {

/// A path that ended by a self-timed trigger.
struct FinishedPath {
  Walker walker;                 ///< at the expected firing (its weight is its probability)
  std::size_t exit = 0;          ///< the transition that fired
  std::size_t segment = 0;       ///< the NOISE draw it fired under (0: the first)
  std::size_t direction = 0;     ///< the quadrature direction of that draw
  std::size_t start = 0;         ///< the start point it came from (0 when the state has one)
  double phase_cycles = 0.0;     ///< settle_phase()'s offset
  /// The variance of where the firing falls after the crossing, in cycles^2
  /// (1/12: uniform within the last cycle; less where the crossing hardly
  /// varies, settle_phases()): along the last step, how far the end spreads.
  double phase_var = 0.0;
  double crossing_c = -1.0;      ///< the crossing's fraction into the last cycle (-1: not crossed by moving toward it)
  Eigen::Vector3d step = Eigen::Vector3d::Zero();  ///< the last cycle's step before the phase move
  double crossing_sd = 0.0;      ///< the crossing time's sd in cycles from the odometry's random error
};

/// One probe of a first-draw circle (engine/direction_arcs): a path stepped
/// at `angle_rad` under the first draw to place a boundary. It carries no
/// weight of its own; where it fired, its crossing is a sample of the
/// duration inside its direction's arc (engine/held_duration).
struct ProbeEnd {
  double angle_rad = 0.0;
  DrawOutcome outcome = kDrawRunning;
  std::size_t cycles = 0;      ///< when it ended (fired: the check that fired)
  double crossing_c = -1.0;    ///< as FinishedPath's, when it fired
  double crossing_sd = 0.0;
};

/// A first-draw circle whose outcome boundaries were bisected: the
/// directions' angles, the boundaries between their arcs (direction_arcs()'s
/// `boundaries`) and the probes.
struct ProbedCircle {
  std::size_t start = 0;  ///< FinishedPath::start of its paths
  std::vector<double> angles, boundaries;
  std::vector<ProbeEnd> probes;
};

struct NoiseQuadrature {
  std::vector<FinishedPath> finished;
  std::vector<ProbedCircle> probed;  ///< the first draw's circles with probes (none: equal arcs everywhere)
  double stuck = 0.0;              ///< mass that never fired an exit: at the cycle cap, standing still (noise_segments.cpp), or a vanishing remainder
  double stuck_x_m = 0.0;          ///< mass-weighted sum of where the stuck walkers were (divide by stuck)
  double stuck_y_m = 0.0;
  /// The same per stratum of the entry error (Walker::stratum; all in 0 when unsplit).
  std::array<double, kErrorStrata> stuck_by_stratum{}, stuck_x_by_stratum{}, stuck_y_by_stratum{};
  std::size_t redraws = 0;         ///< segments after the first that carried mass
  std::vector<PathSample> mean_path;  ///< the mean odometric position every second (finished paths stay put)
  std::size_t cycles_simulated = 0;
};

/// The quadrature of one motion state from `start` (weight 1). For a state
/// without NOISE pass directions = 1 and persistence 0 (held).
/// `record`: each direction's pose and error under the FIRST draw (the whole
/// state when nothing redraws; the caller runs the held quadrature for it
/// otherwise): pose and
/// error after every cycle from the entry, until its exit fires or the robot
/// has come to rest for good (leg_trajectory.hpp; for states a message can
/// interrupt).
NoiseQuadrature noise_quadrature(const PathStepper& stepper, const Walker& start, std::int64_t persistence,
                                 std::size_t directions, std::size_t keep, std::size_t keep_near, std::size_t cap,
                                 LegTrajectory* record = nullptr);

/// The same from several start points (weights summing to 1: where the
/// previous state left the robot, state_analysis.hpp's StartPoint): each
/// start splits into `directions` paths under the first draw (start s's
/// directions turned by s / starts of the quadrature's spacing, so that the
/// starts together sample the circle more finely); `record` then holds
/// starts x directions paths (index s * directions + j) with their weights.
NoiseQuadrature noise_quadrature(const PathStepper& stepper, const std::vector<Walker>& starts,
                                 std::int64_t persistence, std::size_t directions, std::size_t keep,
                                 std::size_t keep_near, std::size_t cap, LegTrajectory* record = nullptr);

/// Reduces weighted walkers (all at the same cycle) to at most `keep`: seeds
/// by weighted farthest point (the heaviest first), two nearest-centre
/// passes, each cluster moment-matched (pose, velocities, turn, error), then
/// the clusters' deviations mapped linearly so that the covariance of their
/// pose and velocities is exactly the children's (merging would otherwise
/// shrink the spread at every redraw), each heading read as the way it faces
/// (its cluster brought within half a turn of the walkers' circular mean
/// heading, every member with it). Deterministic; the total
/// weight and the weighted mean pose are kept.
std::vector<Walker> reduce_walkers(const std::vector<Walker>& walkers, std::size_t keep);

}  // namespace p3at::verifier::engine
