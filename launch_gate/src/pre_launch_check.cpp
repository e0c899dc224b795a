#include "p3at/launch_gate/pre_launch_check.hpp"

#include <time.h>

#include <chrono>
#include <exception>
#include <filesystem>

#include "p3at/launch_gate/mission_hash.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/approximations.hpp"

namespace p3at::gate {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// CPU time of the calling thread, in milliseconds.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) / 1e6;
}

std::string join(const std::vector<std::string>& lines, const char* separator) {
  std::string out;
  for (const std::string& line : lines) out += (out.empty() ? "" : separator) + line;
  return out;
}

/// True, with `result` holding the approximations, when the mission file and
/// the models alone show an approximation the model does not vouch for
/// (verifier::detect_approximations_before_evaluation()). A robot without a
/// model is left to the evaluation, which names it (cannot-run).
bool refuse_before_evaluating(const mission::Mission& mission, const verifier::Models& models,
                              verifier::VerifyResult& result) {
  for (const mission::RobotSpec& robot : mission.robots) {
    if (models.find_robot(robot.name) == nullptr) return false;
  }
  std::vector<verifier::Approximation> found = verifier::detect_approximations_before_evaluation(mission, models);
  if (verifier::all_vouched(found)) return false;
  result = verifier::VerifyResult{};
  result.approximations = std::move(found);
  result.evaluable = false;
  result.go = false;
  return true;
}

}  // namespace

VerdictSource verifier_source() {
  return [](const mission::Mission& mission, const verifier::Models& models, const verifier::VerifyOptions& options,
            const std::vector<std::string>& criteria_files, const verifier::TeamSnapshot* from) {
    return verifier::verify(mission, models, options, criteria_files, from);
  };
}

const char* to_string(CheckStatus status) {
  switch (status) {
    case CheckStatus::go: return "GO";
    case CheckStatus::no_go: return "NO-GO";
    case CheckStatus::bad_input: return "bad-input";
    case CheckStatus::no_models: return "no-models";
    case CheckStatus::cannot_run: return "cannot-run";
    case CheckStatus::cannot_evaluate: return "cannot-evaluate";
  }
  return "?";
}

std::string default_models_path(const std::string& mission_path) {
  const std::filesystem::path folder = std::filesystem::path(mission_path).parent_path();
  return (folder / "models.yaml").string();
}

CheckReport pre_launch_check(const CheckRequest& request, const VerdictSource& source) {
  const auto start = std::chrono::steady_clock::now();
  const double start_cpu_ms = thread_cpu_ms();
  CheckReport report;
  report.mission_path = request.mission_path;
  report.models_path = request.models_path.value_or(default_models_path(request.mission_path));
  auto fail = [&](CheckStatus status, std::string error) {
    report.status = status;
    report.error = std::move(error);
    report.total_ms = ms_since(start);
    report.total_cpu_ms = thread_cpu_ms() - start_cpu_ms;
    return report;
  };

  // The bytes that are hashed are the bytes that are parsed: no file can
  // change between the two.
  const Result<std::string> mission_bytes = read_file_bytes(request.mission_path);
  if (!mission_bytes) return fail(CheckStatus::bad_input, mission_bytes.error().message);
  try {
    report.mission = mission::parse_mission(*mission_bytes, request.mission_path);
  } catch (const std::exception& e) {
    return fail(CheckStatus::bad_input, e.what());
  }

  const Result<std::string> models_bytes = read_file_bytes(report.models_path);
  if (!models_bytes) {
    if (models_bytes.error().code != Error::Code::not_found) return fail(CheckStatus::bad_input, models_bytes.error().message);
    return fail(CheckStatus::no_models,
                "no robot models: " + report.models_path + " does not exist" +
                    (request.models_path ? "" : " (the default: models.yaml beside the mission; pass --models FILE)") +
                    "; without models the launch gate cannot verify the mission");
  }
  try {
    const std::string base_dir = std::filesystem::path(report.models_path).parent_path().string();
    report.models = verifier::parse_models(*models_bytes, report.models_path, base_dir);
  } catch (const std::exception& e) {
    return fail(CheckStatus::bad_input, e.what());
  }
  report.mission_hash = mission_content_hash(*mission_bytes, *models_bytes, report.models->environment.walls);

  const auto verify_start = std::chrono::steady_clock::now();
  if (!request.accept_unvouched && refuse_before_evaluating(*report.mission, *report.models, report.result)) {
    // Not GO whatever the probabilities would say, so they are not computed:
    // the operator hears it in milliseconds, not after minutes of evaluation.
    report.verify_ms = ms_since(verify_start);
    report.refused_before_evaluation = true;
    verifier::locate_in_mission_file(report.result, *mission_bytes, request.mission_path);
    return fail(CheckStatus::cannot_evaluate,
                "the model does not vouch for this mission (" + verifier::unvouched_kinds(report.result.approximations) +
                    "): refused before evaluating it, its P(success) could not be trusted; accept it explicitly "
                    "(--accept-unvouched) to have it evaluated and launched if the probabilities say GO");
  }
  Result<verifier::VerifyResult> verdict =
      source(*report.mission, *report.models, request.options, request.criteria_files, nullptr);
  report.verify_ms = ms_since(verify_start);
  if (!verdict) {
    // A criteria file that does not parse is the operator's input; anything
    // else means these models cannot evaluate this mission.
    const bool bad_input = verdict.error().code == Error::Code::invalid_argument;
    return fail(bad_input ? CheckStatus::bad_input : CheckStatus::cannot_run, verdict.error().message);
  }
  report.result = std::move(verdict.value());
  verifier::locate_in_mission_file(report.result, *mission_bytes, request.mission_path);
  switch (verifier::decision(report.result)) {
    case verifier::Decision::go: report.status = CheckStatus::go; break;
    case verifier::Decision::no_go: report.status = CheckStatus::no_go; break;
    case verifier::Decision::cannot_evaluate:
      // Not GO on a mission the model cannot vouch for, unless the operator
      // says so (and that is logged and published).
      report.accepted_unvouched = request.accept_unvouched;
      report.status = request.accept_unvouched ? CheckStatus::go : CheckStatus::cannot_evaluate;
      if (!request.accept_unvouched) {
        report.error = "the model does not vouch for this mission (" +
                       verifier::unvouched_kinds(report.result.approximations) +
                       "): its P(success) cannot be trusted; accept it explicitly to launch";
      }
      break;
  }
  report.total_ms = ms_since(start);
  report.total_cpu_ms = thread_cpu_ms() - start_cpu_ms;
  return report;
}

gate::GateVerdict make_verdict(const CheckReport& report, bool override_gate) {
  const verifier::VerifyResult& r = report.result;
  gate::GateVerdict v;
  v.mission_hash = report.mission_hash;
  v.p_time = r.p_time;
  v.p_radius = r.p_radius;
  v.p_joint = r.p_joint;
  v.threshold = r.threshold;
  v.tmax_s = r.tmax_s;
  v.rmax_m = r.rmax_m;
  if (override_gate) {
    v.decision = gate::GateDecision::override_go;
    const verifier::Decision said = verifier::decision(r);
    v.detail = std::string("operator override; the verifier said ") +
               (said == verifier::Decision::go ? "GO" : said == verifier::Decision::no_go ? "NO-GO" : "CANNOT-EVALUATE");
    if (!r.failed.empty()) v.detail += ": " + join(r.failed, "; ");
  } else if (report.accepted_unvouched) {
    v.decision = gate::GateDecision::override_go;
    v.detail = "operator accepted unvouched approximations (" + verifier::unvouched_kinds(r.approximations) +
               "); the verifier's probabilities say GO";
  } else {
    v.decision = r.go ? gate::GateDecision::go : gate::GateDecision::no_go;
    v.detail = join(r.failed, "; ");
  }
  return v;
}

}  // namespace p3at::gate
