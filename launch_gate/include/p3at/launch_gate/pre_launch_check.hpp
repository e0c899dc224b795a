#pragma once
/// The pre-launch check: the same on every robot (mission_exec) and on the
/// operator's station (`vipars gate`): load the mission and the robot models,
/// hash them, verify the mission against its criteria (with the operator's
/// overrides), and say GO or NO-GO. docs/launch-gate.md.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/launch_gate/gate_verdict.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::gate {

/// Where verdicts come from: verifier::verify() in production (verifier_source()),
/// anything with the same signature in tests. Called from one thread at a time.
using VerdictSource = std::function<Result<verifier::VerifyResult>(
    const mission::Mission& mission, const verifier::Models& models, const verifier::VerifyOptions& options,
    const std::vector<std::string>& criteria_files, const verifier::TeamSnapshot* from)>;

/// verifier::verify itself.
VerdictSource verifier_source();

/// The models file used when none is given: `models.yaml` in the mission file's folder.
std::string default_models_path(const std::string& mission_path);

struct CheckRequest {
  std::string mission_path;
  std::optional<std::string> models_path;  ///< default: default_models_path(mission_path)
  verifier::VerifyOptions options;         ///< tmax_s / rmax_m / threshold override the mission's criteria
  std::vector<std::string> criteria_files; ///< extra criteria (PARS criterion files), as for `vipars verify`
  /// The operator accepts a mission the model does not vouch for (an
  /// unvouched approximation, docs/verifier.md): its GO stands, logged and
  /// published as OVERRIDE. Without it such a mission is cannot_evaluate.
  bool accept_unvouched = false;
};

enum class CheckStatus {
  go,          ///< verified: p_joint >= threshold and every criterion holds
  no_go,       ///< verified: it does not
  bad_input,   ///< the mission, models or a criteria file does not load (file:line:column in `error`)
  no_models,   ///< there is no models file: without models the gate cannot run
  cannot_run,  ///< the verifier could not evaluate this mission with these models
  /// The mission has an approximation the model does not vouch for
  /// (VerifyResult::approximations): not GO unless the operator accepts
  /// (CheckRequest::accept_unvouched). One the mission file and models show by
  /// themselves refuses it before any evaluation (CheckReport::
  /// refused_before_evaluation); one only the evaluation finds (robots racing,
  /// teammates driving near the path, places merged over the branch budget)
  /// refuses a GO, and a NO-GO stays no_go.
  cannot_evaluate,
};
/// "GO", "NO-GO", "bad-input", "no-models", "cannot-run", "cannot-evaluate"
const char* to_string(CheckStatus status);

struct CheckReport {
  CheckStatus status = CheckStatus::cannot_run;
  std::string error;          ///< for bad_input / no_models / cannot_run: what went wrong, naming the file
  std::string mission_path;
  std::string models_path;
  std::string mission_hash;   ///< mission_content_hash() of both files; empty when they did not load
  std::optional<mission::Mission> mission;  ///< as loaded (the executive runs this very value)
  std::optional<verifier::Models> models;
  verifier::VerifyResult result;  ///< the verifier's answer (go / no_go / cannot_evaluate), approximations located
  /// GO only because the operator accepted unvouched approximations.
  bool accepted_unvouched = false;
  /// cannot_evaluate without evaluating: the mission file and the models
  /// already show an unvouched approximation, so no probability could make it
  /// GO. `result` holds the approximations (located) and no probabilities.
  bool refused_before_evaluation = false;
  double verify_ms = 0.0;     ///< the verifier call alone, or the look before it that refused (wall time)
  double total_ms = 0.0;      ///< reading, hashing, parsing and verifying: the gate's decision time (wall time)
  /// The same as total_ms in CPU time of the calling thread: what the decision
  /// costs, unaffected by other processes competing for the CPU.
  double total_cpu_ms = 0.0;

  bool verified() const { return status == CheckStatus::go || status == CheckStatus::no_go; }
  /// The verifier answered: verified, or cannot_evaluate. `result` holds the
  /// approximations; its probabilities only when !refused_before_evaluation.
  bool evaluated() const { return verified() || status == CheckStatus::cannot_evaluate; }
};

/// Runs the check. Never throws: load errors come back as bad_input with
/// "file:line:column: what was expected".
CheckReport pre_launch_check(const CheckRequest& request, const VerdictSource& source);

/// This robot's verdict for the team link. With `override_gate` the decision
/// is OVERRIDE whatever the verifier said (the probabilities are still the
/// verifier's, and `detail` says what it had decided); so is a GO the
/// operator got by accepting unvouched approximations (`detail` names them).
/// Precondition: report.verified().
gate::GateVerdict make_verdict(const CheckReport& report, bool override_gate);

}  // namespace p3at::gate
