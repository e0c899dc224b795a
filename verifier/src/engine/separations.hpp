#pragma once
/// Where each robot is over mission time, and the two robots' relative
/// positions at the same moments, for separation (safety) criteria (eq. 6:
/// "for all times, the robots apart").
///
/// Why timelines: a robot's path through a state used to be compared, as
/// soon as it entered the state, with where each teammate stood at that
/// moment (frozen there for the whole state). A teammate crossing the
/// robot's lane twenty seconds later was then never near it: on
/// tests/data/accuracy/crossing_behind verify said P(always more than 2.5 m
/// apart) 1.000 where 4,000 runs give 0.67. Each robot now keeps its own
/// predicted positions at mission times (its states' paths, cut where the
/// next event took it out of a state), and the pairs are compared at the
/// same times when the branch ends.

#include <cstddef>
#include <vector>

#include "p3at/verifier/mog.hpp"
#include "p3at/verifier/outcome.hpp"

namespace p3at::verifier::engine {

/// The robot's predicted true position at a mission time (the branch clock's
/// mean): mean and covariance, the covariance including the spread of its
/// NOISE paths at that moment (which carries the spread of how far along its
/// leg it has got).
struct TimedPosition {
  double time_s = 0.0;
  Gaussian2 position;
  /// For how long from here its error can be taken as one fixed draw
  /// (SeparationSample::rigid_s).
  double rigid_s = 0.0;
};

/// A robot's predicted positions in time order.
class Timeline {
 public:
  /// Adds a position at time_s; what was predicted from time_s on (the rest
  /// of a state the robot has left) is dropped first.
  void note(double time_s, const Gaussian2& position, double rigid_s);
  const std::vector<TimedPosition>& points() const { return points_; }
  bool empty() const { return points_.empty(); }
  /// Linear interpolation between the points; before the first, the first;
  /// after the last, the last (the robot stands where it ended).
  Gaussian2 at(double time_s) const;
  /// The rigid span of the point in force at time_s (the last at or before it).
  double rigid_at(double time_s) const;

 private:
  std::vector<TimedPosition> points_;
};

/// The pairs' relative positions (position(i) - position(j), covariances
/// added: the robots' errors are independent) at every time either robot has
/// a point, for each pair i < j; samples whose mean distance is beyond
/// `horizon_m` are left out (they cannot matter to a criterion about robots
/// coming close), but for the first of them (SeparationSample::beyond_horizon).
/// SeparationSample::joined says whether the sample follows
/// the pair's previous kept sample directly (so the segment between them is
/// the pair's interpolated motion). Samples are grouped by pair, in time
/// order within a pair.
std::vector<SeparationSample> pair_separations(const std::vector<const Timeline*>& robots, double horizon_m);

}  // namespace p3at::verifier::engine
