#pragma once
/// How the pre-launch check is shown: one human-readable block (vipars gate,
/// mission_exec's refusal) and grep-able key=value fields for log lines.

#include <string>

#include "p3at/hal/team_link.hpp"
#include "p3at/launch_gate/gate_verdict.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"

namespace p3at::gate {

/// The GO / NO-GO block: the decision, the mission and its hash, P(time),
/// P(radius), P(joint) against the threshold, extra criteria, the predicted
/// completion and each robot's prediction, every failed criterion, and the
/// decision time. For a check that could not run: the decision and the error.
/// For a mission refused before evaluation: the unvouched approximations,
/// where each is, and no probabilities. Ends with a newline.
std::string format_check(const CheckReport& report);

/// `decision=GO p_time=.. p_radius=.. p_joint=.. threshold=.. tmax_s=.. rmax_m=.. hash=.. decision_ms=..`;
/// refused before evaluation: `decision=cannot-evaluate evaluated=false hash=.. unvouched=KINDS decision_ms=..`
std::string check_fields(const CheckReport& report);

/// `robot=.. decision=.. p_joint=.. threshold=.. hash=<first 16 digits>`
std::string verdict_fields(const gate::GateVerdict& verdict);

}  // namespace p3at::gate
