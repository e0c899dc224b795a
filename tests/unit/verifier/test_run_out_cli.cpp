// The stop after the final trigger (docs/verifier.md): a robot's final
// position is where it comes to rest after entering its final state, in the
// verifier (the still state's braking from the speed it fired at) as in the
// validation (runs stepped until every robot stands still). On
// tests/data/run_out (one 4 m leg at 0.5 m/s into a 0.3 m dropoff, AtGoal
// 0.3 m, NOISE off; models from `vipars calibrate --world` on its world),
// `vipars verify`'s mean final distance against `vipars simulate`'s over 300
// runs. Before the run-out, verify put the robot where AtGoal fired, about
// 0.27 m from its goal; at rest it is about 0.07 m. About 1 s.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

namespace {

std::string vipars() { return p3at::test::vipars_binary(); }

std::string data(const std::string& name) { return std::string(P3AT_SOURCE_DIR) + "/tests/data/run_out/" + name; }

}  // namespace

TEST_CASE("a fast approach's final distance: verify's braking run-out against 300 simulated runs at rest") {
  const auto v = p3at::test::run_command(vipars() + " verify " + data("mission.yaml") + " --models " +
                                         data("models.yaml") + " --json");
  REQUIRE(!v.out.empty());
  const nlohmann::json verified = nlohmann::json::parse(v.out);
  const double predicted = verified.at("robots").at(0).at("dist_mean_m").get<double>();

  const auto s = p3at::test::run_command(vipars() + " simulate " + data("mission.yaml") + " --world " +
                                         data("world.yaml") + " --runs 300 --seed 1 --json");
  REQUIRE(s.status == 0);
  const nlohmann::json simulated = nlohmann::json::parse(s.out);
  double sum = 0.0;
  for (const nlohmann::json& run : simulated.at("runs")) sum += run.at("robots").at(0).at("dist_to_goal_m").get<double>();
  const double mean = sum / static_cast<double>(simulated.at("runs").size());

  INFO("verify " << predicted << " m, 300 runs " << mean << " m");
  // Both at rest, well inside the AtGoal radius the robot fired at (0.3 m).
  CHECK(mean < 0.15);
  CHECK(std::abs(predicted - mean) < 0.005);
}
