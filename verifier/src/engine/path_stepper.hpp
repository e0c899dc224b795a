#pragma once
/// One control cycle of a motion state's flow (the period process Sys' of
/// the TR subsystem) for one deterministic NOISE path: the executive's own
/// schemas compute the command from the odometric pose and the sonar
/// readings the sensor model predicts from the true pose, the base model
/// ramps toward it, the error model propagates the true pose's error, and
/// the state's self-timed triggers are checked as the executive checks them.
/// Shared by the held-direction quadrature and the redrawn-NOISE segment
/// quadrature (noise_segments.hpp).

#include <cstddef>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "engine/error_state.hpp"
#include "engine/state_analysis.hpp"
#include "p3at/executive/behaviors.hpp"

namespace p3at::verifier::engine {

/// A path's state at a cycle boundary.
struct Walker {
  BaseState q;                  ///< odometric pose and velocities now
  BaseState before;             ///< the same one cycle earlier (for the trigger's crossing phase)
  ErrorState error;             ///< the true pose's error now
  double turned_rad = 0.0;      ///< odometric turn accumulated since the state's entry
  double turned_before_rad = 0.0;
  std::size_t cycles = 0;       ///< cycles since the state's entry
  /// Variance (in cycles^2) of when AtGoal and HasTurned cross their
  /// thresholds, from the odometry's relative random error: the simulator
  /// multiplies each update's odometric translation and rotation by
  /// (1 + N(0, sd^2)) (docs/simulator.md), so it is the odometric pose, the
  /// one the triggers read, that jitters. A cycle's error n moves the believed
  /// distance to the goal by n times the cycle's radial step, and the time
  /// left by that over the radial speed, which is the step over one cycle: so
  /// every cycle of progress toward the threshold adds sd^2 cycles^2,
  /// whatever the speed (a slow approach does not magnify it: its small steps
  /// carry small errors). Likewise for the turn.
  double at_goal_jitter_var = 0.0;
  double turn_jitter_var = 0.0;
  double weight = 1.0;          ///< quadrature weight (probability) of this path
  /// Which slab of the entry error this path stands for (engine/error_strata;
  /// 0: the middle, or no split). Paths of different strata are never merged.
  std::uint8_t stratum = 0;
};

class PathStepper {
 public:
  PathStepper(const StateContext& context, std::size_t state);

  /// The self-timed exit that holds now (checked from the first cycle on), if any.
  std::optional<std::size_t> fired(const Walker& w) const;
  /// Moves the walker's pose to the trigger's expected firing within its
  /// last cycle (crossing interpolated, firing on average half a cycle
  /// after it) and returns that offset in cycles, in [-0.5, 0.5]. When the
  /// trigger was crossed by moving toward it, `crossing_c` is the crossing's
  /// fraction into the last cycle (else -1) and `step` the last cycle's step
  /// (x, y, heading) before the move, for settle_phases() (trigger_phase.hpp);
  /// `crossing_sd` the crossing time's standard deviation in cycles from the
  /// odometry's random error (Walker::at_goal_jitter_var, turn_jitter_var), else 0.
  double settle_phase(Walker& w, std::size_t transition, double* crossing_c = nullptr,
                      Eigen::Vector3d* step = nullptr, double* crossing_sd = nullptr) const;
  /// One cycle under the NOISE direction (cos a, sin a) of the walker's
  /// angle a: it holds one for many cycles, so its caller computes them once.
  void step(Walker& w, const exec::Vec2<double>& noise_direction) const;

  /// Where the flow is strongly nonlinear in the pose: within the goal's
  /// slow-down (dropoff plus half a metre) or within AVOID_OBSTACLES' reach
  /// of an obstacle. The redrawn-NOISE quadrature keeps more walkers there.
  bool delicate(const Walker& w) const;

  const mission::GoToGuardedParams* go() const { return go_; }
  /// True when nothing around the robot moves during the state (no driving
  /// teammate comes near): a path standing still then stays still.
  bool static_surroundings() const;
  /// How far from the robot's true centre an obstacle can still push it
  /// (AVOID_OBSTACLES' sphere beyond the body, from the sonar ring); 0 for a Spin.
  double avoid_reach_m() const { return avoid_reach_m_; }
  /// Cycles between mean-path samples (one second).
  std::size_t sample_every() const { return sample_every_; }

 private:
  /// An obstacle (a wall, a still teammate, or a driving teammate where it is
  /// at the walker's cycle) within reach_m of the true position (x, y).
  bool obstacle_within(const Walker& w, double x_m, double y_m, double reach_m) const;

  const StateContext& ctx_;
  std::size_t state_;
  exec::BehaviorConfig config_;
  const mission::GoToGuardedParams* go_ = nullptr;
  const mission::SpinParams* spin_ = nullptr;
  std::size_t sample_every_ = 10;
  double max_range_m_ = 5.0;
  double avoid_reach_m_ = 0.0;
  double cast_m_ = 5.0;
};

}  // namespace p3at::verifier::engine
