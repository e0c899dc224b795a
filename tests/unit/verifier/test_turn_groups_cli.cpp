// Where a robot ends when its last leg is turned into one way on some runs
// and the other way on the rest (engine/state_analysis.cpp,
// grouped_weight_ends). With the robot's rotation scale off by a few percent
// the two groups' true ends lie 0.3-1.2 m apart, each group tight, while
// their odometric ends share the AtGoal circle. The mission is gen_7582's
// robot1 (the fresh sweep's seeds 7561-7640) alone in its world: a 45-degree
// spin, then a leg whose goal lies 179 degrees behind; 15 % of 1,000 runs
// turn left and end 1.2 m from the rest. The end points were slabs by
// bearing around the goal, which averaged the two groups into one blob.
// `vipars verify` against 300 `vipars validate` runs (under a second in
// release).
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_json.hpp"
#include "cli_run.hpp"

namespace {

using p3at::test::run_json;

std::string data(const std::string& mission, const std::string& file) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/turn_groups/" + mission + "/" + file;
}

struct Both {
  double verify = 0.0, runs = 0.0;
};

/// P(r <= rmax) by verify and by 300 runs.
Both p_radius(const std::string& mission, double rmax) {
  const std::string vipars = p3at::test::vipars_binary();
  const std::string r = " --rmax " + std::to_string(rmax) + " --json";
  const nlohmann::json verified =
      run_json(vipars + " verify " + data(mission, "mission.yaml") + " --models " + data(mission, "models.yaml") + r);
  const nlohmann::json runs = run_json(vipars + " validate " + data(mission, "mission.yaml") + " --world " +
                                       data(mission, "world.yaml") + " --trials 300 --seed 1" + r);
  Both b{verified.at("p_radius").get<double>(), runs.at("p_radius").get<double>()};
  MESSAGE(mission << ": P(r <= " << rmax << " m) verify " << b.verify << ", 300 runs " << b.runs);
  CHECK(verified.at("work_cutoff_mass").get<double>() == 0.0);
  CHECK(runs.at("failed_runs").get<int>() == 0);
  return b;
}

}  // namespace

TEST_CASE("spin_then_turn_about: the runs that turn the other way end apart, and the rest stay tight") {
  const Both b = p_radius("spin_then_turn_about", 0.8);
  REQUIRE(b.runs > 0.1);
  REQUIRE(b.runs < 0.3);
  // Measured: verify 0.254 against 300 runs' 0.180 (1,000 runs: 0.171);
  // with the slabs by bearing 0.445.
  CHECK(std::abs(b.verify - b.runs) < 0.12);
}
