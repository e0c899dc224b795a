#pragma once
/// Teammates that drive while a robot's state is analysed, as obstacles that
/// move with time (docs/verifier.md, "The team").
///
/// A teammate driving a GoToGuarded leg cannot be a fixed obstacle: pinned
/// where its leg began it would block a robot headed for the spot it just
/// left, and left out (as before this file) it parks in another robot's lane
/// mid-leg unseen, or drives across it. So when robot i enters a GoToGuarded
/// state, each teammate j in a GoToGuarded leg becomes a body that follows
/// j's predicted mean TRUE path over time: j's StateAnalysis::path (its mean
/// odometric position every second since its entry) plus j's true-pose error
/// mean (interpolated from its entry's to its end's along the distance
/// driven: the error grows with the distance, a heading error turns the path
/// about its start), placed at each of i's cycles by the time since j's entry
/// (the branch clock minus j's entry clock, means, plus i's cycles). When j's
/// leg ends (its pending exit's mean time) j stays at its mean end pose while
/// the states after it hold still (Stop, Notify, Spin, final): for good when
/// it waits there for a message or has finished, for their expected length
/// when they lead on by themselves to another leg (a Notify's acknowledgement,
/// a Spin's turn), and drops out then, as at once when its next state is a
/// leg (a leg is analysed only when the robot gets there). A teammate that
/// holds still when robot i enters its state but drives off by its own
/// triggers stands at its mean true pose until then, and on from there as
/// above along the leg it drives off on (sequencer's still_then_off).
///
/// It is one-way: j's path was predicted without i (i does not push j aside
/// or slow it down), and it is j's MEAN path, a single body, not the spread
/// of where j may be.

#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "engine/base_motion.hpp"
#include "engine/sonar_model.hpp"
#include "engine/state_analysis.hpp"

namespace p3at::verifier::engine {

/// A body's true pose.
struct BodyPose {
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;
};

/// One teammate's body over the analysed robot's cycles (counted from its
/// state's entry): at poses[n] for n < poses.size(), then at `rest` until
/// cycle `rest_until` (exclusive; kForGood: for the rest of the state), then
/// gone.
struct MovingBody {
  static constexpr std::size_t kForGood = std::numeric_limits<std::size_t>::max();
  std::vector<BodyPose> poses;
  BodyPose rest;
  std::size_t rest_until = 0;

  /// Where the body is at cycle n, or null when it is not an obstacle then
  /// (gone, or driving: a pose whose x is NaN, see follow_legs()).
  const BodyPose* at(std::size_t cycle) const {
    if (cycle < poses.size()) return std::isnan(poses[cycle].x_m) ? nullptr : &poses[cycle];
    return cycle < rest_until ? &rest : nullptr;
  }
};

/// A teammate's GoToGuarded leg as the sequencer knows it when another robot
/// enters a state (times from that robot's entry): the leg it drives now, or
/// the next one it will drive (predicted ahead, engine sequencer).
struct TeammateLeg {
  const std::vector<PathSample>* path = nullptr;  ///< mean odometric position every second since its entry
  BaseState start;                                 ///< odometric pose at its entry
  BaseState end;                                   ///< mean odometric pose at its leg's end
  Eigen::Vector3d error_start = Eigen::Vector3d::Zero();  ///< true pose's error mean at its entry
  Eigen::Vector3d error_end = Eigen::Vector3d::Zero();    ///< ... and at its leg's end
  /// When it entered the leg (<= 0: it is driving it now) and when the leg's
  /// exit fires (means); ends_in_s is infinity when the leg has no self-timed
  /// exit (it drives to its goal and waits there for a message).
  double entered_s = 0.0;
  double ends_in_s = std::numeric_limits<double>::infinity();
  /// How long it holds still where the leg ended (the states after it that
  /// hold still: Stop, Notify, Spin, final) before it drives again (its next
  /// leg, if given, else it drops out); infinity: for good (a final state, or
  /// one it leaves only on a message); 0: the next state is a leg.
  double still_for_s = 0.0;
};

/// The teammate's body at each of the analysed robot's cycles (cycle_s
/// apart) over its legs, in order (the second entered when the first's
/// stillness after it ends, and so on; the last one's end decides the rest).
MovingBody follow_legs(const std::vector<TeammateLeg>& legs, double cycle_s);

/// True when the body comes within `reach_m` of the segment a..b (its centre
/// within reach plus the body's half-diagonal) at any cycle: a body that never
/// does cannot be seen by a robot moving along a..b.
bool passes_near(const MovingBody& body, double ax, double ay, double bx, double by, double reach_m);

/// The moving teammates of one state's analysis.
class MovingBodies {
 public:
  void add(MovingBody body) { bodies_.push_back(std::move(body)); }
  bool empty() const { return bodies_.empty(); }
  std::size_t size() const { return bodies_.size(); }

  /// True when some body's outline is within `reach_m` of (x, y) at `cycle`
  /// (exact: distance to the rectangle, not to its centre).
  bool within(std::size_t cycle, double x_m, double y_m, double reach_m) const;
  /// Appends the four sides of every body within `reach_m` of (x, y) at `cycle`.
  void append_within(std::size_t cycle, double x_m, double y_m, double reach_m, std::vector<Segment>& out) const;
  /// Two independent 64-bit hashes (FNV-1a and a multiply-xorshift) of every
  /// body's poses, rest pose and rest time, bit for bit: a key for caching a
  /// state's analysis (engine/sequencer).
  std::pair<std::uint64_t, std::uint64_t> fingerprint() const;

 private:
  std::vector<MovingBody> bodies_;
};

/// Distance from (x, y) to a P3-AT body's outline at `pose` (0 inside it).
double distance_to_body(const BodyPose& pose, double x_m, double y_m);

}  // namespace p3at::verifier::engine
