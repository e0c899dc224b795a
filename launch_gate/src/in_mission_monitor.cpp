#include "p3at/launch_gate/in_mission_monitor.hpp"

#include <algorithm>

#include "p3at/common/log.hpp"
#include "p3at/launch_gate/check_report.hpp"
#include "p3at/common/number_format.hpp"

namespace p3at::gate {
namespace {
constexpr const char* kLog = "gate";
}  // namespace

InMissionMonitor::InMissionMonitor(const mission::Mission& mission, std::size_t self,
                                   const mission::Criteria& criteria, Reverifier& reverifier, GateTeamLink& link)
    : mission_(mission), self_(self), criteria_(criteria), reverifier_(reverifier), link_(link),
      progress_(mission, self) {}

void InMissionMonitor::on_transition(const exec::TransitionEvent& event) {
  if (executive_ == nullptr) return;
  const mission::RobotSpec& spec = mission_.robots.at(self_);
  progress_.observe_teammates(event.t_s, link_.teammate_telemetry(), link_.teammate_status());
  progress_.observe_self(event.t_s, event.to, event.pose, spec.is_final(event.to));
  verifier::TeamSnapshot snapshot = progress_.snapshot(event.t_s, executive_->messages(), link_);
  reverifier_.request(std::move(snapshot), spec.name + ":" + spec.states.at(event.to).name);
}

std::optional<std::string> InMissionMonitor::on_poll() {
  if (executive_ == nullptr || !executive_->started()) return std::nullopt;
  const exec::RobotExecutive& ex = *executive_;
  const double t_s = ex.elapsed_s();
  progress_.observe_self(t_s, ex.state_index(), ex.pose(), ex.outcome().phase == exec::Phase::finished);
  progress_.observe_teammates(t_s, link_.teammate_telemetry(), link_.teammate_status());
  std::optional<std::string> abort_reason;
  for (const Reverification& answer : reverifier_.take()) {
    if (auto reason = handle(answer); reason && !abort_reason) abort_reason = std::move(reason);
  }
  return abort_reason;
}

std::optional<std::string> InMissionMonitor::handle(const Reverification& answer) {
  const std::string& robot = mission_.robots.at(self_).name;
  if (!answer.result) {
    log::warn(kLog, "event=reverify-error robot=" + robot + " t_s=" + format_fixed(answer.at_s, 1) + " cause=" +
                        answer.cause + " error=\"" + answer.result.error().message + "\"");
    return std::nullopt;
  }
  const verifier::VerifyResult& r = answer.result.value();
  ++answers_;
  latest_p_ = r.p_joint;
  lowest_p_ = std::min(lowest_p_.value_or(r.p_joint), r.p_joint);
  max_compute_ms_ = std::max(max_compute_ms_, answer.compute_ms);
  log::info(kLog, "event=reverify robot=" + robot + " t_s=" + format_fixed(answer.at_s, 1) + " cause=" + answer.cause +
                      " p_time=" + format_fixed(r.p_time, 4) + " p_radius=" + format_fixed(r.p_radius, 4) +
                      " p_joint=" + format_fixed(r.p_joint, 4) + " abort_threshold=" + format_fixed(criteria_.abort_threshold, 4) +
                      " compute_ms=" + format_fixed(answer.compute_ms, 2));
  const bool below = criteria_.abort_threshold > 0.0 && r.p_joint < criteria_.abort_threshold;
  std::optional<std::string> abort_reason;
  if (below && executive_->running()) {
    const std::string what = "re-verification at t_s=" + format_fixed(answer.at_s, 1) + ": P(success) " +
                             format_fixed(r.p_joint, 4) + " < abort threshold " + format_fixed(criteria_.abort_threshold, 4);
    switch (criteria_.abort_action) {
      case mission::AbortAction::stop_and_notify:
        if (!abort_requested_) {
          abort_requested_ = true;
          log::warn(kLog, "event=reverify-abort robot=" + robot + " action=stop_and_notify reason=\"" + what + "\"");
          abort_reason = what;
        }
        break;
      case mission::AbortAction::continue_and_warn:
        log::warn(kLog, "event=reverify-warning robot=" + robot + " action=continue_and_warn reason=\"" + what + "\"");
        link_.set_note("warning: " + what + "; continuing");
        break;
    }
  }
  link_.set_p_success(r.p_joint);  // republishes this robot's status with it (and the note)
  return abort_reason;
}

}  // namespace p3at::gate
