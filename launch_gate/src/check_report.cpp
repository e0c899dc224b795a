#include "p3at/launch_gate/check_report.hpp"
#include "p3at/common/number_format.hpp"

#include <cstdio>

namespace p3at::gate {

namespace {

std::string line(const std::string& label, const std::string& value) {
  std::string padded = "  " + label;
  if (padded.size() < 44) padded.resize(44, ' ');
  return padded + value + "\n";
}

std::string approximation_lines(const std::vector<verifier::Approximation>& approximations) {
  std::string out;
  for (const verifier::Approximation& a : approximations) {
    out += std::string("  ") + (a.vouched ? "approximation (vouched) " : "UNVOUCHED approximation ") +
           verifier::to_string(a.kind) + ": " + a.robot_name + (a.state.empty() ? "" : " '" + a.state + "'") +
           (a.where.empty() ? "" : " at " + a.where) + ": " + a.detail + "\n";
  }
  return out;
}

std::string decision_time_line(const CheckReport& report) {
  return line("decision time", format_fixed(report.total_ms, 1) + " ms (verifier " + format_fixed(report.verify_ms, 1) +
                                   " ms; " + format_fixed(report.total_cpu_ms, 1) + " ms of CPU)");
}

/// A refusal without evaluation: what was found and where, no probabilities
/// (none was computed, and none could have made the mission GO).
std::string format_refused_before_evaluation(const CheckReport& report, const std::string& name) {
  std::string out = "CANNOT EVALUATE  mission " + name +
                    ": the model does not vouch for it; refused before evaluating (no probability computed)\n";
  out += line("mission file", report.mission_path);
  out += line("robot models", report.models_path);
  out += line("content hash", report.mission_hash);
  out += approximation_lines(report.result.approximations);
  out += "  cannot evaluate: " + report.error + "\n";
  out += decision_time_line(report);
  return out;
}

}  // namespace

std::string format_check(const CheckReport& report) {
  std::string out;
  const std::string name = report.mission ? report.mission->name : report.mission_path;
  if (!report.evaluated()) {
    out += std::string(to_string(report.status)) + "  mission " + name + ": the launch gate cannot decide\n";
    out += "  " + report.error + "\n";
    return out;
  }
  const verifier::VerifyResult& r = report.result;
  if (report.refused_before_evaluation) return format_refused_before_evaluation(report, name);
  if (report.status == CheckStatus::cannot_evaluate) {
    out += "CANNOT EVALUATE  mission " + name + ": the probabilities say GO, but the model does not vouch for it\n";
  } else if (report.accepted_unvouched) {
    out += "GO (operator accepted unvouched approximations)  mission " + name + "\n";
  } else {
    out += std::string(report.status == CheckStatus::go ? "GO" : "NO-GO") + "  mission " + name + "\n";
  }
  out += line("mission file", report.mission_path);
  out += line("robot models", report.models_path);
  out += line("content hash", report.mission_hash);
  out += line("P(done by Tmax = " + format_fixed(r.tmax_s, 1) + " s)", format_fixed(r.p_time, 4));
  out += line("P(every robot within Rmax = " + format_fixed(r.rmax_m, 2) + " m)", format_fixed(r.p_radius, 4));
  out += line("P(success) = P(both)", format_fixed(r.p_joint, 4) + (r.p_joint >= r.threshold ? "  >= " : "  < ") +
                                          "threshold " + format_fixed(r.threshold, 4));
  out += line("P(success) decided", format_fixed(r.p_joint_decided, 4) + " at " + format_fixed(r.decided_tmax_s, 2) + " s, " +
                                        format_fixed(r.decided_rmax_m, 3) + " m (" + verifier::decision_margin_text(r) +
                                        "; the gate decides on this)");
  for (const verifier::CriterionVerdict& c : r.criteria) {
    out += line("criterion " + c.name, format_fixed(c.probability, 4) + (c.holds ? "  holds" : "  FAILS") + " (needs " +
                                           format_fixed(c.required, 4) + ")");
  }
  if (r.branches > 0 && (r.completion_sd_s > 0.0 || r.completion_mean_s > 0.0)) {
    out += line("predicted completion", format_fixed(r.completion_mean_s, 1) + " s +- " + format_fixed(r.completion_sd_s, 1) + " s");
  }
  for (const verifier::RobotPrediction& robot : r.robots) {
    if (!robot.finishes) {
      out += line(robot.name + " predicted", "BLOCKED: never reaches a final state (below)");
      continue;
    }
    out += line(robot.name + " predicted", "done at " + format_fixed(robot.finish_mean_s, 1) + " s +- " +
                                               format_fixed(robot.finish_sd_s, 1) + ", ends " + format_fixed(robot.dist_mean_m, 2) +
                                               " m from its goal, P(within Rmax) " + format_fixed(robot.p_radius, 4));
  }
  for (const verifier::BlockedRobot& b : r.blocked) {
    out += line(b.name + " blocked", "P " + format_fixed(b.probability, 4) + " " + b.why + " in state '" + b.state_name +
                                         "' near (" + format_fixed(b.x_m, 2) + ", " + format_fixed(b.y_m, 2) + ")" +
                                         (b.where.empty() ? "" : " " + b.where));
  }
  for (const std::string& failed : r.failed) out += "  failed: " + failed + "\n";
  out += approximation_lines(r.approximations);
  if (report.status == CheckStatus::cannot_evaluate) out += "  cannot evaluate: " + report.error + "\n";
  out += decision_time_line(report);
  return out;
}

std::string check_fields(const CheckReport& report) {
  std::string out = std::string("decision=") + to_string(report.status);
  if (report.refused_before_evaluation) {
    out += " evaluated=false hash=" + report.mission_hash +
           " unvouched=" + verifier::unvouched_kinds(report.result.approximations);
  } else if (report.evaluated()) {
    const verifier::VerifyResult& r = report.result;
    out += " p_time=" + format_fixed(r.p_time, 4) + " p_radius=" + format_fixed(r.p_radius, 4) + " p_joint=" + format_fixed(r.p_joint, 4) +
           " threshold=" + format_fixed(r.threshold, 4) + " tmax_s=" + format_fixed(r.tmax_s, 1) + " rmax_m=" + format_fixed(r.rmax_m, 2) +
           " hash=" + report.mission_hash + " evaluable=" + (r.evaluable ? "true" : "false");
    const std::string unvouched = verifier::unvouched_kinds(r.approximations);
    if (!unvouched.empty()) out += " unvouched=" + unvouched;
    if (report.accepted_unvouched) out += " accepted_unvouched=true";
  }
  out += " decision_ms=" + format_fixed(report.total_ms, 2) + " verify_ms=" + format_fixed(report.verify_ms, 2) +
         " decision_cpu_ms=" + format_fixed(report.total_cpu_ms, 2);
  return out;
}

std::string verdict_fields(const gate::GateVerdict& verdict) {
  return "robot=" + verdict.robot + " decision=" + gate::to_string(verdict.decision) + " p_joint=" +
         format_fixed(verdict.p_joint, 4) + " threshold=" + format_fixed(verdict.threshold, 4) +
         " hash=" + verdict.mission_hash.substr(0, 16);
}

}  // namespace p3at::gate
