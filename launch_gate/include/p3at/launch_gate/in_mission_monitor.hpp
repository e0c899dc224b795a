#pragma once
/// In-mission re-verification (beyond the paper; docs/launch-gate.md): at each
/// FSA transition of this robot, re-verify the mission from where the team now
/// is, publish the updated probability in this robot's status, and below the
/// mission's abort threshold take its abort action:
///   stop_and_notify    stop this robot; its aborted status stops the team
///   continue_and_warn  log a warning and say so in the status, keep going
/// Everything here runs on the executive's thread, between its cycles' steps
/// (the verifier itself runs on the Reverifier's worker).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "p3at/executive/robot_executive.hpp"
#include "p3at/launch_gate/gate_team_link.hpp"
#include "p3at/launch_gate/reverifier.hpp"
#include "p3at/launch_gate/team_progress.hpp"
#include "p3at/mission/mission.hpp"

namespace p3at::gate {

class InMissionMonitor {
 public:
  /// `criteria` gives abort_threshold (0 = never abort) and abort_action.
  /// `mission`, `reverifier` and `link` must outlive the monitor.
  InMissionMonitor(const mission::Mission& mission, std::size_t self, const mission::Criteria& criteria,
                   Reverifier& reverifier, GateTeamLink& link);

  /// The executive whose robot this is; before its first cycle.
  void attach(const exec::RobotExecutive& executive) { executive_ = &executive; }

  /// ExecutiveOptions::on_transition: requests a re-verification from the new state.
  void on_transition(const exec::TransitionEvent& event);

  /// GateTeamLink::after_poll (every cycle): tracks the team, handles finished
  /// re-verifications. Returns the abort reason the first time stop_and_notify
  /// applies (the caller aborts the mission with it); nullopt otherwise.
  std::optional<std::string> on_poll();

  std::uint64_t answers() const { return answers_; }
  std::optional<double> latest_p() const { return latest_p_; }
  std::optional<double> lowest_p() const { return lowest_p_; }
  double max_compute_ms() const { return max_compute_ms_; }

 private:
  std::optional<std::string> handle(const Reverification& answer);

  const mission::Mission& mission_;
  std::size_t self_;
  mission::Criteria criteria_;
  Reverifier& reverifier_;
  GateTeamLink& link_;
  const exec::RobotExecutive* executive_ = nullptr;
  TeamProgress progress_;
  bool abort_requested_ = false;
  std::uint64_t answers_ = 0;
  std::optional<double> latest_p_;
  std::optional<double> lowest_p_;
  double max_compute_ms_ = 0.0;
};

}  // namespace p3at::gate
