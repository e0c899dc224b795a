// Issue 13 item 8: a separation (safety) criterion, the paper's eq. (6) read
// as "at every moment", against 4,000 simulated runs of a mission written for
// it (tests/data/separation/crossing_behind: robot2 crosses robot1's lane on
// robot1's word, 20 s later, a few metres ahead of it). Each run's closest
// approach is measured by the validation (the smallest true centre distance
// at any cycle); verify's P(never within d) must follow their curve within the
// issue's 0.05, and never say GO (>= 0.8) where the runs' 95 % interval is
// clearly below (< 0.78).
//
// Before each robot's predicted positions were compared at the same times
// (docs/verifier.md, "Separation criteria"), verify compared robot1's path
// with robot2 frozen where it waited, and said P(always more than 2.5 m
// apart) = 1.000 where the runs give 0.708: a wrong GO on a safety criterion.
//
// Label `accuracy` (release stage only): 4,000 runs take a few seconds in
// release and minutes under the sanitizers.
#include <doctest/doctest.h>


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/team_sim/wilson.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/separation.hpp"
#include "p3at/verifier/verify.hpp"

namespace verifier = p3at::verifier;

namespace {

std::string data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/data/separation/crossing_behind/" + name;
}

/// The closest_approach_m column of `vipars validate --csv`.
std::vector<double> closest_approaches(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::istringstream h(line);
    for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  }
  const auto column = static_cast<std::size_t>(std::find(header.begin(), header.end(), "closest_approach_m") - header.begin());
  REQUIRE(column < header.size());
  std::vector<double> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t k = 0; k <= column; ++k) std::getline(row, cell, ',');
    out.push_back(std::stod(cell));
  }
  return out;
}

}  // namespace

TEST_CASE("crossing_behind: P(never within d) against 4,000 runs' closest approaches") {
  const std::filesystem::path csv = p3at::test::scratch_path("separation.csv");
  const auto v = p3at::test::run_command(p3at::test::vipars_binary() + " validate " + data("mission.yaml") + " --world " +
                                         data("world.yaml") + " --trials 4000 --seed 1 --jobs 2 --csv " + csv.string());
  REQUIRE(v.status == 0);
  const std::vector<double> runs = closest_approaches(p3at::test::read_file(csv.string()));
  std::filesystem::remove(csv);
  REQUIRE(runs.size() == 4000);

  const auto mission = p3at::mission::load_mission_file(data("mission.yaml"));
  const auto models = verifier::load_models_file(data("models.yaml"));
  const auto outcome = verifier::evaluate_system(mission, models);
  REQUIRE(outcome.ok());

  double worst = 0.0;
  for (int cm = 150; cm <= 300; cm += 10) {
    const double d = cm / 100.0;
    const auto apart = static_cast<std::uint64_t>(std::count_if(runs.begin(), runs.end(), [&](double c) { return c > d; }));
    const auto ci = p3at::team_sim::wilson_interval(apart, runs.size());
    const double measured = static_cast<double>(apart) / static_cast<double>(runs.size());
    const double predicted = verifier::probability_no_pair_within(outcome.value(), d);
    MESSAGE("d " << d << " m: verify " << predicted << ", runs " << measured << " (95 % up to " << ci.high << ")");
    // No over-confident point (the cross-check's definition): a GO at 0.8
    // where the runs' whole 95 % interval is clearly below it.
    CHECK_FALSE((predicted >= 0.8 && ci.high < 0.78));
    worst = std::max(worst, std::abs(predicted - measured));
  }
  MESSAGE("worst |verify - runs| " << worst);
  CHECK(worst <= 0.05);  // the bound for a curve; measured 0.020 (at 2.1 m), 27 November 2026

  // The criterion file reads the same probability (one pair: the whole team).
  const std::string criterion = "criterion apart\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>) | "
                                "Delay<t3> ; (Delay<t4> # At<robot2, q>)\nconstraints\n  t1, t3 > 0\n  P(|p - q| > 2.5) > 0.8\n";
  const std::filesystem::path crit = p3at::test::scratch_path("separation.crit");
  p3at::test::write_file(crit.string(), criterion);
  const auto r = p3at::test::run_command(p3at::test::vipars_binary() + " verify " + data("mission.yaml") + " --models " +
                                         data("models.yaml") + " --criterion " + crit.string() + " --json");
  std::filesystem::remove(crit);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const double from_file = j.at("criteria").at(0).at("probability").get<double>();
  // Decided as the gate decides Rmax: 1 % and at least a step (both robots'
  // top speed for one cycle: 0.06 m here) stricter.
  const double step = 2.0 * verifier::decision_floors(mission, models).radius_m;
  CHECK(step == doctest::Approx(0.06));
  CHECK(from_file == doctest::Approx(verifier::probability_no_pair_within(
                                         outcome.value(), verifier::decided_separation(2.5, true, step)))
                         .epsilon(1e-9));
  CHECK(from_file < 0.75);  // the runs' fraction is 0.708; it said 1.000 before
  CHECK_FALSE(j.at("criteria").at(0).at("holds").get<bool>());
}
