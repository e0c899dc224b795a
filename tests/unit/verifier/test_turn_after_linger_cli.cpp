// A leg that some runs leave facing far off the rest, before a leg whose goal
// is behind the robot (data/turn_after_linger: robot1 of the generated
// mission gen_5157). About 12 % of runs turn around the other way and, with
// the robot's rotation scale, end 0.45 m from where the others end. The
// verifier used to carry the first leg's ends from paths that held their
// NOISE past its redraw (none of them leaves at those headings) and to merge
// them by where they ended around the goal (averaging the headings that
// decide the turn): every path turned the same way, P(r <= 0.72 m) 1.00
// where the runs give 0.88. `vipars verify`'s radius curve against 4,000
// `vipars validate` runs of the same mission (about 1 s in release).
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

const std::string kGrid = " --rmax-range 0.4:1.2:0.04";

std::string data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/turn_after_linger/" + name;
}

std::vector<double> radius_curve(const std::string& command) {
  const auto r = p3at::test::run_command(command);
  REQUIRE(!r.out.empty());
  const nlohmann::json j = nlohmann::json::parse(r.out);
  return j.at("grid").at("p_radius").get<std::vector<double>>();
}

}  // namespace

TEST_CASE("the runs that turn around the other way after a lingering leg are predicted") {
  const std::string vipars = p3at::test::vipars_binary();
  const std::vector<double> verified =
      radius_curve(vipars + " verify " + data("mission.yaml") + " --models " + data("models.yaml") + " --json" + kGrid);
  const std::vector<double> runs = radius_curve(vipars + " validate " + data("mission.yaml") + " --world " +
                                                data("world.yaml") + " --trials 4000 --seed 1 --json" + kGrid);
  REQUIRE(verified.size() == runs.size());
  REQUIRE(verified.size() == 21);
  double worst = 0.0;
  for (std::size_t k = 0; k < runs.size(); ++k) worst = std::max(worst, std::abs(verified[k] - runs[k]));
  MESSAGE("max |verify - runs| over the radius curve: " << worst);
  CHECK(worst <= 0.1);
  // The plateau between the two groups (0.72 to 0.88 m): the runs' 0.88.
  for (std::size_t k = 8; k <= 12; ++k) {
    CAPTURE(k);
    CHECK(runs[k] == doctest::Approx(0.88).epsilon(0.03));
    CHECK(std::abs(verified[k] - runs[k]) <= 0.03);
  }
}
