// A mode the start points merge away, and the refusal that stands in for it
// (data/late_arrival_pinned: robot2 of the CI gate's gen_9, its patrol driven
// once as three legs). About 9 % of runs circle patrol_b's goal under the
// NOISE before they reach it, arrive late facing north instead of east, turn
// the other way into leg1 and are pinned against the end of a free-standing
// wall: 1,000 runs P(t <= 120 s, r <= 4 m) 0.914. The eight equally likely
// points a leg hands the next average that mode with its neighbours, and
// verify's blocked mass is 0.012 (P 0.988; docs/verifier.md, "A late mode
// merged away by the carried start points"). Its approximations
// (noise-redrawn-strong, may-get-trapped) are ones the model does not vouch
// for, so at the mission's threshold 0.95 the answer is "cannot evaluate":
// never GO, which is what this holds, whatever the model's figures become.
// `vipars verify` and `vipars gate` against 1,000 `vipars validate` runs (about 3 s in release).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_json.hpp"
#include "cli_run.hpp"

namespace {

std::string data(const std::string& file) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/late_arrival_pinned/" + file;
}

}  // namespace

TEST_CASE("late_arrival_pinned: the runs fall short of the threshold, and neither verify nor the gate says GO") {
  const std::string vipars = p3at::test::vipars_binary();
  const nlohmann::json runs = p3at::test::run_json(vipars + " validate " + data("mission.yaml") + " --world " +
                                                   data("world.yaml") + " --trials 1000 --seed 1 --json");
  // The truth: a GO at 0.95 would be wrong (measured 0.914, its 95 % interval up to 0.930;
  // 82 runs pinned or still moving at the timeout).
  CHECK(runs.at("p_joint_ci_high").get<double>() < 0.95);
  CHECK(runs.at("failed_runs").get<int>() >= 50);

  const std::string verify = vipars + " verify " + data("mission.yaml") + " --models " + data("models.yaml");
  const p3at::test::CommandOutcome text = p3at::test::run_command(verify);
  MESSAGE("vipars verify exit " << text.status);
  CHECK((text.status == 1 || text.status == 3));  // NO-GO or cannot evaluate, never GO (0)
  const nlohmann::json verified = p3at::test::run_json(verify + " --json");
  MESSAGE("verify P " << verified.at("p_joint").get<double>() << ", blocked " << verified.at("blocked_mass").get<double>()
                      << ", decision " << verified.at("decision").get<std::string>());
  CHECK(verified.at("decision").get<std::string>() != "go");

  const p3at::test::CommandOutcome gate =
      p3at::test::run_command(vipars + " gate " + data("mission.yaml") + " --models " + data("models.yaml"));
  CHECK((gate.status == 1 || gate.status == 3));
}
