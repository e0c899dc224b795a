// The pre-launch check: files in, GO / NO-GO out, with the content hash of
// exactly the bytes that were parsed; every way it can fail to decide; the
// verdict and the report built from it. Verdicts are injected (scripted), and
// the real verifier is checked to give the same answer through the gate as
// when called directly.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "child_process.hpp"
#include "gate_test_util.hpp"
#include "p3at/launch_gate/check_report.hpp"
#include "p3at/launch_gate/mission_hash.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"
#include "p3at/mission/loader.hpp"

using namespace p3at;
using gate::CheckStatus;

namespace {

const std::string kRelayMission = std::string(P3AT_SOURCE_DIR) + "/examples/relay/mission.yaml";

const std::string kModels = R"(models:
  version: 1
robots:
  - name: robot1
    motion: {trans_sd_per_sqrt_m: 0.02, rot_sd_per_sqrt_rad: 0.03}
  - name: robot2
    motion: {trans_sd_per_sqrt_m: 0.02, rot_sd_per_sqrt_rad: 0.03}
communication:
  delivery_ms: [{weight: 1.0, mean: 5, sd: 2}]
  ack_ms: [{weight: 1.0, mean: 10, sd: 3}]
)";

void write(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// A folder with the relay mission and (optionally) models.yaml beside it.
struct Folder {
  std::string dir = test::scratch_path("gate-check");
  std::string mission = dir + "/mission.yaml";
  std::string models = dir + "/models.yaml";
  explicit Folder(bool with_models = true) {
    std::filesystem::create_directories(dir);
    write(mission, gate::read_file_bytes(kRelayMission).value());
    if (with_models) write(models, kModels);
  }
  ~Folder() { std::filesystem::remove_all(dir); }
};

gate::CheckRequest request(const Folder& f) {
  gate::CheckRequest r;
  r.mission_path = f.mission;
  return r;
}

}  // namespace

TEST_CASE("models default to models.yaml beside the mission") {
  CHECK(gate::default_models_path("/a/b/mission.yaml") == "/a/b/models.yaml");
  CHECK(gate::default_models_path("mission.yaml") == "models.yaml");
}

TEST_CASE("GO: the verifier's answer, the content hash of both files, the loaded mission and models") {
  Folder f;
  test::ScriptedVerifier scripted;
  const auto report = gate::pre_launch_check(request(f), scripted.source());
  REQUIRE(report.status == CheckStatus::go);
  CHECK(report.models_path == f.models);
  CHECK(report.mission_hash ==
        gate::mission_content_hash(gate::read_file_bytes(f.mission).value(), kModels, report.models->environment.walls));
  CHECK(report.mission->name == "relay");
  CHECK(report.models->robots.size() == 2);
  CHECK(report.result.p_joint == doctest::Approx(0.9));
  CHECK(report.total_ms >= report.verify_ms);
  CHECK(report.total_cpu_ms > 0.0);  // parsing two files is not free
  REQUIRE(scripted.calls.size() == 1);
  CHECK_FALSE(scripted.calls[0].snapshot.has_value());  // from the mission's start
}

TEST_CASE("NO-GO, with the operator's overrides and criteria files passed to the verifier") {
  Folder f;
  test::ScriptedVerifier scripted;
  scripted.p_joint = 0.5;
  auto req = request(f);
  req.options.tmax_s = 12.0;
  req.options.threshold = 0.6;
  req.criteria_files = {"extra.crit"};
  const auto report = gate::pre_launch_check(req, scripted.source());
  CHECK(report.status == CheckStatus::no_go);
  REQUIRE(scripted.calls.size() == 1);
  CHECK(scripted.calls[0].options.tmax_s == 12.0);
  CHECK(scripted.calls[0].options.threshold == 0.6);
  CHECK(scripted.calls[0].criteria_files == std::vector<std::string>{"extra.crit"});
  CHECK(report.result.tmax_s == doctest::Approx(12.0));
}

TEST_CASE("a different models file or a one-byte change to the mission changes the hash") {
  Folder f;
  test::ScriptedVerifier scripted;
  const std::string base = gate::pre_launch_check(request(f), scripted.source()).mission_hash;
  write(f.models, kModels + "# tuned\n");
  CHECK(gate::pre_launch_check(request(f), scripted.source()).mission_hash != base);
  write(f.models, kModels);
  CHECK(gate::pre_launch_check(request(f), scripted.source()).mission_hash == base);
  write(f.mission, gate::read_file_bytes(kRelayMission).value() + "\n");
  CHECK(gate::pre_launch_check(request(f), scripted.source()).mission_hash != base);
}

TEST_CASE("no models: the gate cannot run, and says where it looked") {
  Folder f(false);
  test::ScriptedVerifier scripted;
  auto report = gate::pre_launch_check(request(f), scripted.source());
  CHECK(report.status == CheckStatus::no_models);
  CHECK(report.error.find(f.models) != std::string::npos);
  CHECK(report.error.find("--models") != std::string::npos);
  CHECK(scripted.calls.empty());
  auto req = request(f);
  req.models_path = f.dir + "/other.yaml";
  report = gate::pre_launch_check(req, scripted.source());
  CHECK(report.status == CheckStatus::no_models);
  CHECK(report.error.find("other.yaml") != std::string::npos);
}

TEST_CASE("bad input: mission or models that do not load, with file:line:column") {
  Folder f;
  test::ScriptedVerifier scripted;
  write(f.models, "models:\n  version: 1\nrobots:\n  - name: robot1\n    motion: {trans_scale: north}\n");
  auto report = gate::pre_launch_check(request(f), scripted.source());
  CHECK(report.status == CheckStatus::bad_input);
  CHECK(report.error.find(f.models + ":5:") != std::string::npos);
  write(f.models, kModels);
  write(f.mission, "mission:\n  name: x\n  bogus_key: 1\n");
  report = gate::pre_launch_check(request(f), scripted.source());
  CHECK(report.status == CheckStatus::bad_input);
  CHECK(report.error.find(f.mission + ":") != std::string::npos);
  auto req = request(f);
  req.mission_path = f.dir + "/missing.yaml";
  report = gate::pre_launch_check(req, scripted.source());
  CHECK(report.status == CheckStatus::bad_input);
  CHECK(report.error.find("missing.yaml") != std::string::npos);
  CHECK(scripted.calls.empty());
}

TEST_CASE("a verifier error: bad input when it is about the input, cannot-run otherwise") {
  Folder f;
  test::ScriptedVerifier scripted;
  scripted.error = make_error(Error::Code::invalid_argument, "extra.crit:3:1: expected a comparison");
  auto report = gate::pre_launch_check(request(f), scripted.source());
  CHECK(report.status == CheckStatus::bad_input);
  CHECK(report.error == "extra.crit:3:1: expected a comparison");
  scripted.error = make_error(Error::Code::state, "every branch deadlocks");
  report = gate::pre_launch_check(request(f), scripted.source());
  CHECK(report.status == CheckStatus::cannot_run);
  CHECK_FALSE(report.verified());
  CHECK(gate::format_check(report).find("every branch deadlocks") != std::string::npos);
}

TEST_CASE("the verdict for the team link: GO, NO-GO with the failed criteria, OVERRIDE saying what it overrode") {
  Folder f;
  test::ScriptedVerifier scripted;
  scripted.p_joint = 0.42;
  const auto report = gate::pre_launch_check(request(f), scripted.source());
  auto v = gate::make_verdict(report, false);
  CHECK(v.decision == gate::GateDecision::no_go);
  CHECK(v.mission_hash == report.mission_hash);
  CHECK(v.p_joint == doctest::Approx(0.42));
  CHECK(v.threshold == doctest::Approx(0.8));
  CHECK(v.detail.find("scripted") != std::string::npos);
  v = gate::make_verdict(report, true);
  CHECK(v.decision == gate::GateDecision::override_go);
  CHECK(v.detail.find("operator override; the verifier said NO-GO") == 0);
  scripted.p_joint = 0.95;
  v = gate::make_verdict(gate::pre_launch_check(request(f), scripted.source()), false);
  CHECK(v.decision == gate::GateDecision::go);
  CHECK(v.detail.empty());
}

TEST_CASE("the printed report: decision, probabilities against the threshold, failed criteria, decision time") {
  Folder f;
  test::ScriptedVerifier scripted;
  scripted.p_joint = 0.42;
  const auto report = gate::pre_launch_check(request(f), scripted.source());
  const std::string text = gate::format_check(report);
  CHECK(text.rfind("NO-GO  mission relay\n", 0) == 0);
  CHECK(text.find("P(done by Tmax = 60.0 s)") != std::string::npos);
  CHECK(text.find("0.4200  < threshold 0.8000") != std::string::npos);
  CHECK(text.find("failed: P(joint) below threshold (scripted)") != std::string::npos);
  CHECK(text.find("decision time") != std::string::npos);
  CHECK(text.find(report.mission_hash) != std::string::npos);
  const std::string fields = gate::check_fields(report);
  CHECK(fields.find("decision=NO-GO p_time=0.4200 p_radius=1.0000 p_joint=0.4200 threshold=0.8000") == 0);
}

namespace {

/// The relay with robot1's NOISE at gain 0.25, redrawn every 10 cycles on its
/// 2 m leg: noise-redrawn-strong, an approximation the model does not vouch
/// for, which the mission file shows by itself.
std::string relay_with_strong_noise() {
  std::string text = gate::read_file_bytes(kRelayMission).value();
  const std::string leg = "goal: [3.0, 1.0], dropoff_m: 0.5}";
  const auto at = text.find(leg);
  REQUIRE(at != std::string::npos);
  text.replace(at, leg.size(), "goal: [3.0, 1.0], dropoff_m: 0.5, noise_gain: 0.25}");
  return text;
}

}  // namespace

TEST_CASE("an unvouched approximation the mission file shows: refused before the verifier runs, located; "
          "accepted, it is evaluated") {
  Folder f;
  write(f.mission, relay_with_strong_noise());
  test::ScriptedVerifier scripted;
  const auto report = gate::pre_launch_check(request(f), scripted.source());
  CHECK(report.status == CheckStatus::cannot_evaluate);
  CHECK(report.refused_before_evaluation);
  CHECK(scripted.calls.empty());  // no probability could have made it GO: none was computed
  CHECK_FALSE(report.verified());
  CHECK(report.evaluated());
  CHECK(report.mission_hash.size() == 64);  // the files were read and hashed all the same
  REQUIRE_FALSE(report.result.approximations.empty());
  const verifier::Approximation& a = report.result.approximations.front();
  CHECK(a.kind == verifier::ApproximationKind::noise_redrawn_strong);
  CHECK(a.robot_name == "robot1");
  CHECK(a.state == "drive");
  CHECK(a.where.rfind(f.mission + ":", 0) == 0);
  CHECK(report.error.find("noise-redrawn-strong") != std::string::npos);
  CHECK(report.error.find("refused before evaluating") != std::string::npos);

  const std::string text = gate::format_check(report);
  CHECK(text.rfind("CANNOT EVALUATE  mission relay: the model does not vouch for it; refused before evaluating", 0) == 0);
  CHECK(text.find("UNVOUCHED approximation noise-redrawn-strong: robot1 'drive' at " + f.mission + ":") !=
        std::string::npos);
  CHECK(text.find("P(done by") == std::string::npos);  // no probability is printed: none was computed
  CHECK(text.find("P(success) =") == std::string::npos);
  CHECK(text.find(report.mission_hash) != std::string::npos);
  CHECK(text.find("decision time") != std::string::npos);
  const std::string fields = gate::check_fields(report);
  CHECK(fields.rfind("decision=cannot-evaluate evaluated=false hash=" + report.mission_hash +
                         " unvouched=noise-redrawn-strong decision_ms=",
                     0) == 0);

  // The operator accepts the approximation: now the probabilities decide.
  auto accepted = request(f);
  accepted.accept_unvouched = true;
  scripted.p_joint = 0.5;
  const auto evaluated = gate::pre_launch_check(accepted, scripted.source());
  CHECK(scripted.calls.size() == 1);
  CHECK_FALSE(evaluated.refused_before_evaluation);
  CHECK(evaluated.status == CheckStatus::no_go);
}

TEST_CASE("an unvouched approximation only the evaluation finds: evaluated first, and a GO becomes cannot-evaluate") {
  // Robots racing, or teammates driving near the path, show only in the
  // evaluation: the gate cannot refuse those before it.
  Folder f;
  test::ScriptedVerifier scripted;
  gate::VerdictSource racing = [&scripted](const mission::Mission& mission, const verifier::Models& models,
                                           const verifier::VerifyOptions& options,
                                           const std::vector<std::string>& criteria,
                                           const verifier::TeamSnapshot* from) -> Result<verifier::VerifyResult> {
    Result<verifier::VerifyResult> r = scripted.source()(mission, models, options, criteria, from);
    verifier::Approximation a;
    a.kind = verifier::ApproximationKind::robots_racing;
    a.robot_name = "robot1";
    a.state = "drive";
    a.element = verifier::MissionElement::state;
    a.detail = "scripted race";
    a.vouched = false;
    r->approximations.push_back(a);
    r->evaluable = false;
    return r;
  };
  const auto report = gate::pre_launch_check(request(f), racing);
  CHECK(scripted.calls.size() == 1);
  CHECK_FALSE(report.refused_before_evaluation);
  CHECK(report.status == CheckStatus::cannot_evaluate);
  CHECK(gate::format_check(report).rfind("CANNOT EVALUATE  mission relay: the probabilities say GO", 0) == 0);
  CHECK(gate::check_fields(report).find("p_joint=0.9000") != std::string::npos);
}

TEST_CASE("the real verifier through the gate gives what verify() gives; a Tmax too tight is NO-GO") {
  Folder f;
  const auto report = gate::pre_launch_check(request(f), gate::verifier_source());
  REQUIRE_MESSAGE(report.verified(), report.error);
  const auto direct = verifier::verify(mission::load_mission_file(f.mission), *report.models, {});
  REQUIRE(direct.ok());
  CHECK(report.result.p_joint == doctest::Approx(direct->p_joint));
  CHECK(report.result.go == direct->go);
  auto tight = request(f);
  tight.options.tmax_s = 1.0;  // two 2 m drives in one second: impossible
  const auto refused = gate::pre_launch_check(tight, gate::verifier_source());
  REQUIRE(refused.verified());
  CHECK(refused.status == CheckStatus::no_go);
  CHECK(refused.result.p_time < 0.01);
  CHECK_FALSE(refused.result.failed.empty());
}
