// A teammate that drives past a robot while it circles its goal: a gap the
// model has (docs/verifier.md, "A teammate driving past a robot that circles
// its goal"), and the gate must refuse, not GO, on it. The mission is the fresh
// sweep's gen_7567 cut to three robots. robot4 misses its 0.1 m AtGoal circle
// and circles its goal until robot2's recall; robot1 drives past 0.78 m from
// that goal meanwhile, pushes robot4 round, and the extra turning (robot4's
// wheels turn it 5 % short) sends its later leg off by ~2 m. Each evaluation
// ignores the other's driving, so verify's probabilities say GO while the runs
// say 0.15: the listed, unvouched `teammates-moving-near-path` is what turns it
// into "cannot evaluate". Without robot1 verify and the runs agree, which is
// what shows the gap is the teammate's driving. `vipars verify` against 150
// `vipars validate` runs (about a second in release).
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_json.hpp"
#include "cli_run.hpp"

namespace {

using p3at::test::run_json;

std::string data(const std::string& file) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/teammate_past_orbit/" + file;
}

std::string verify_command(const std::string& mission) {
  return p3at::test::vipars_binary() + " verify " + data(mission) + " --models " + data("models.yaml");
}

nlohmann::json runs(const std::string& mission) {
  return run_json(p3at::test::vipars_binary() + " validate " + data(mission) + " --world " + data("world.yaml") +
                  " --trials 150 --seed 1 --json");
}

double robot_distance(const nlohmann::json& doc, const std::string& robot, const char* key) {
  for (const auto& r : doc.at("robots")) {
    if (r.at("name") == robot) return r.at(key).get<double>();
  }
  FAIL("no robot " << robot);
  return 0.0;
}

bool lists_unvouched(const nlohmann::json& verified, const std::string& kind, const std::string& robot,
                     const std::string& state) {
  for (const auto& a : verified.at("approximations")) {
    if (a.at("kind") == kind && a.at("robot") == robot && a.at("state") == state && !a.at("vouched").get<bool>()) {
      return true;
    }
  }
  return false;
}

}  // namespace

TEST_CASE("teammate_past_orbit: verify's probabilities would GO where the runs fail, and the gate refuses") {
  const auto plain = p3at::test::run_command(verify_command("mission.yaml"));
  CHECK(plain.status == 3);  // cannot evaluate: GO by the probabilities, an approximation unvouched
  const nlohmann::json verified = run_json(verify_command("mission.yaml") + " --json");
  const nlohmann::json validated = runs("mission.yaml");
  const double v = verified.at("p_joint").get<double>(), r = validated.at("p_joint").get<double>();
  MESSAGE("P(t <= 120 s, r <= 3 m): verify " << v << ", 150 runs " << r << "; robot4 "
                                             << robot_distance(verified, "robot4", "dist_mean_m") << " m against "
                                             << robot_distance(validated, "robot4", "dist_mean_m") << " m");
  // Measured: verify 0.981 against 1,000 runs' 0.151 (robot4 1.91 m from
  // its goal against 4.01 m).
  REQUIRE(v >= 0.9);
  REQUIRE(r < 0.5);
  CHECK(verified.at("decision") == "cannot-evaluate");
  CHECK(lists_unvouched(verified, "teammates-moving-near-path", "robot4", "leg1"));
  CHECK(lists_unvouched(verified, "teammates-moving-near-path", "robot1", "leg2"));
}

TEST_CASE("teammate_past_orbit without robot1: verify puts robot4 where the runs do") {
  const nlohmann::json verified = run_json(verify_command("without_robot1.yaml") + " --json");
  const nlohmann::json validated = runs("without_robot1.yaml");
  const double v = robot_distance(verified, "robot4", "dist_mean_m");
  const double r = robot_distance(validated, "robot4", "dist_mean_m");
  MESSAGE("robot4 alone with robot2: verify " << v << " m from its goal, 150 runs " << r << " m");
  // Measured: verify 1.91 m, 300 runs 1.84 m.
  CHECK(std::abs(v - r) < 0.3);
  CHECK(validated.at("failed_runs").get<int>() == 0);
}
