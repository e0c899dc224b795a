#pragma once
/// Where the team is during the mission, as one robot knows it: its own
/// state and odometry from the executive, its teammates' from their telemetry
/// and status on the team link, the messages from its MessageBook. Turned
/// into a verifier::TeamSnapshot for in-mission re-verification
/// (docs/launch-gate.md). Pure: times come in as arguments (mission seconds).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "p3at/executive/schemas.hpp"
#include "p3at/executive/triggers.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::gate {

/// One robot's progress as this robot believes it.
struct RobotProgress {
  std::size_t state = 0;        ///< index into RobotSpec::states
  double entered_s = 0.0;       ///< mission time the state was entered (for a teammate: first heard in it)
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;  ///< odometric pose, world frame
  double travelled_m = 0.0;     ///< odometric path length since launch (teammates: between telemetry samples)
  double turned_rad = 0.0;      ///< absolute odometric rotation since launch
  bool finished = false;
  bool heard = false;           ///< a teammate: any telemetry received yet
  std::vector<bool> visited;    ///< states seen, indexed like RobotSpec::states
};

class TeamProgress {
 public:
  /// Every robot starts in its initial state at its start pose, at time 0.
  /// `mission` must outlive this object.
  TeamProgress(const mission::Mission& mission, std::size_t self);

  /// This robot, every cycle and at every transition (with the new state).
  void observe_self(double t_s, std::size_t state, const exec::Pose<double>& pose, bool finished);
  /// The teammates: their latest telemetry (pose, state name, cycle count) and
  /// status (finished). Telemetry naming an unknown robot or state is ignored.
  void observe_teammates(double t_s, const std::vector<hal::Telemetry>& telemetry,
                         const std::vector<hal::TeamStatus>& status);

  /// The snapshot at `elapsed_s`. Messages: this robot's own from `book` and
  /// `link` (sent; acknowledged by every recipient = received); one it
  /// received counts as sent, and as received when it was its only recipient;
  /// between teammates, a message counts as sent once its sender was seen in
  /// the Notify state, and as received once the sender was seen to leave it.
  verifier::TeamSnapshot snapshot(double elapsed_s, const exec::MessageBook& book, const hal::TeamLink& link) const;

  const RobotProgress& robot(std::size_t index) const { return robots_.at(index); }

 private:
  void move(RobotProgress& r, double t_s, std::size_t state, double x_m, double y_m, double theta_rad);

  const mission::Mission& mission_;
  std::size_t self_;
  std::vector<RobotProgress> robots_;
  std::vector<std::optional<std::uint64_t>> last_cycles_;  ///< teammates' telemetry cycle counter last used
};

}  // namespace p3at::gate
