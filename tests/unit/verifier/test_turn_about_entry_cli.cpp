// A leg entered facing about, from start points of unequal weight
// (data/turn_about_entry: the generated mission gen_7016). Its first leg
// leaves the robot's heading spread over some 25 degrees, almost straight
// away from the second leg's goal; the second leg's start points are split
// into the robot turning right (weight 0.97) and left (0.03). The first NOISE
// draw's directions used to be dealt out among those start points, each
// taking its start's weight: two directions carried 97 % of the mass, the
// NOISE was no longer uniform, and the mission was predicted 0.21 s early
// (27.10 s against the runs' 27.31 s), its time curve 0.35 off at 27 s.
// `vipars verify`'s time curve against 1,000 `vipars validate` runs (about
// a second in release).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

const std::string kGrid = " --tmax-range 25:30:0.25";

std::string data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/turn_about_entry/" + name;
}

nlohmann::json run_json(const std::string& command) {
  const auto r = p3at::test::run_command(command);
  REQUIRE(!r.out.empty());
  return nlohmann::json::parse(r.out);
}

}  // namespace

TEST_CASE("a leg entered facing about: its NOISE directions stay uniform whatever the start points weigh") {
  const std::string vipars = p3at::test::vipars_binary();
  const nlohmann::json verified =
      run_json(vipars + " verify " + data("mission.yaml") + " --models " + data("models.yaml") + " --json" + kGrid);
  const nlohmann::json runs = run_json(vipars + " validate " + data("mission.yaml") + " --world " +
                                       data("world.yaml") + " --trials 1000 --seed 1 --json" + kGrid);
  const double verify_mean = verified.at("completion_mean_s").get<double>();
  const double runs_mean = runs.at("completion_mean_s").get<double>();
  INFO("completion: verify " << verify_mean << " ± " << verified.at("completion_sd_s").get<double>()
                             << " s, 1,000 runs " << runs_mean << " ± " << runs.at("completion_sd_s").get<double>()
                             << " s");
  CHECK(std::abs(verify_mean - runs_mean) < 0.15);  // the runs' mean is known to ±0.02 s

  const auto v = verified.at("grid").at("p_time").get<std::vector<double>>();
  const auto r = runs.at("grid").at("p_time").get<std::vector<double>>();
  REQUIRE(v.size() == 21);
  REQUIRE(r.size() == v.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) worst = std::max(worst, std::abs(v[k] - r[k]));
  MESSAGE("max |verify - runs| over the time curve (25-30 s): " << worst);
  CHECK(worst <= 0.12);
}
