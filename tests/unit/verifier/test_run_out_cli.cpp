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

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

namespace {

std::string open_data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/data/accuracy_open/noise_at_goal/" + name;
}

/// The fraction of `sorted` at or below x.
double empirical_cdf(const std::vector<double>& sorted, double x) {
  return static_cast<double>(std::upper_bound(sorted.begin(), sorted.end(), x) - sorted.begin()) /
         static_cast<double>(sorted.size());
}

struct Gap {
  double worst = 0.0;  ///< largest |verify - runs| of P(r <= Rmax) on verify's grid
  double at_m = 0.0;   ///< the Rmax where it is
};

/// Verify's P(r <= Rmax) curve (`vipars verify --json`) against the runs'
/// distances at rest, `sorted`.
Gap radius_gap(const nlohmann::json& verified, const std::vector<double>& sorted) {
  const auto& rmax = verified.at("grid").at("rmax");
  const auto& p_radius = verified.at("grid").at("p_radius");
  REQUIRE(rmax.size() == p_radius.size());
  Gap g;
  for (std::size_t j = 0; j < rmax.size(); ++j) {
    const double gap = std::abs(p_radius[j].get<double>() - empirical_cdf(sorted, rmax[j].get<double>()));
    if (gap > g.worst) g = {gap, rmax[j].get<double>()};
  }
  return g;
}

}  // namespace

TEST_CASE("a strong NOISE at the AtGoal circle: each path runs out its own braking, so the distance at rest spreads") {
  // tests/data/accuracy_open/noise_at_goal: a 3 m leg at 0.45 m/s with NOISE
  // gain 0.25 held for the whole leg. A path pushed forward fires at about
  // 0.4 m/s and brakes 14 cm toward the goal, one pushed aside fires at
  // 0.15 m/s and brakes 2 cm: the distance at rest spreads over about 10 cm
  // (400 runs: 10 % below 6 cm, 90 % below 17 cm). When every path braked
  // like the mean, verify's curve rose within 11-17 cm and was 0.18 off the
  // runs'; with each path's own run-out, about 0.05.
  const auto s = p3at::test::run_command(vipars() + " simulate " + open_data("mission.yaml") + " --world " +
                                         open_data("world.yaml") + " --runs 400 --seed 5 --json");
  REQUIRE(s.status == 0);
  const nlohmann::json simulated = nlohmann::json::parse(s.out);
  std::vector<double> dist;
  for (const nlohmann::json& run : simulated.at("runs")) {
    if (run.at("outcome") == "success") dist.push_back(run.at("robots").at(0).at("dist_to_goal_m").get<double>());
  }
  REQUIRE(dist.size() > 390);
  std::sort(dist.begin(), dist.end());
  const double q10 = dist[dist.size() / 10], q90 = dist[dist.size() * 9 / 10];
  CHECK(q90 - q10 > 0.07);  // the spread this test is about is there in the runs

  const auto v = p3at::test::run_command(vipars() + " verify " + open_data("mission.yaml") + " --models " +
                                         open_data("models.yaml") + " --rmax-range 0.02:0.22:0.01 --json");
  REQUIRE(!v.out.empty());
  const Gap gap = radius_gap(nlohmann::json::parse(v.out), dist);
  INFO("largest |verify - runs| of P(r <= Rmax): " << gap.worst << " at " << gap.at_m << " m; runs' q10 " << q10
                                                     << " q90 " << q90);
  // 400 runs' own error is about 0.025 (1 sd) at the curve's middle.
  CHECK(gap.worst < 0.1);
}

TEST_CASE("the same mission's completion time and distance at rest together: the joint surface follows the paths") {
  // Issue 13 item 7. A path NOISE pushes toward the goal arrives early and
  // runs out closer to it; one pushed aside arrives late and farther off: in
  // the runs, nearly every one done by 7.4 s rests within 15 cm. Verify took
  // the two as independent within its branch and under-stated their joint by
  // up to 0.21 (at Tmax 7.3 s, Rmax 0.13 m: 0.078 against the runs' 0.29);
  // with each final point's time score (engine/time_position.hpp) 0.14. The
  // rest is where verify's eight points lie (two early paths rest just past
  // 15 cm, two late ones just inside).
  const auto s = p3at::test::run_command(vipars() + " simulate " + open_data("mission.yaml") + " --world " +
                                         open_data("world.yaml") + " --runs 400 --seed 5 --json");
  REQUIRE(s.status == 0);
  const nlohmann::json simulated = nlohmann::json::parse(s.out);
  std::vector<std::pair<double, double>> runs;  // (completion time, distance at rest) of the successful runs
  for (const nlohmann::json& run : simulated.at("runs")) {
    if (run.at("outcome") == "success") {
      runs.emplace_back(run.at("time_s").get<double>(), run.at("robots").at(0).at("dist_to_goal_m").get<double>());
    }
  }
  const double total = static_cast<double>(simulated.at("runs").size());
  REQUIRE(runs.size() > 390);

  const auto v = p3at::test::run_command(vipars() + " verify " + open_data("mission.yaml") + " --models " +
                                         open_data("models.yaml") + " --tmax-range 6.8:9.4:0.1 --rmax-range 0.02:0.22:0.01 --json");
  REQUIRE(!v.out.empty());
  const nlohmann::json grid = nlohmann::json::parse(v.out).at("grid");
  double worst = 0.0, worst_t = 0.0, worst_r = 0.0;
  for (std::size_t i = 0; i < grid.at("tmax").size(); ++i) {
    const double t = grid.at("tmax")[i].get<double>();
    for (std::size_t j = 0; j < grid.at("rmax").size(); ++j) {
      const double r = grid.at("rmax")[j].get<double>();
      const double both = static_cast<double>(std::count_if(runs.begin(), runs.end(), [&](const auto& x) {
                            return x.first <= t + 1e-9 && x.second <= r;
                          })) / total;
      const double gap = std::abs(grid.at("p_joint")[i][j].get<double>() - both);
      if (gap > worst) std::tie(worst, worst_t, worst_r) = std::make_tuple(gap, t, r);
    }
  }
  INFO("largest |verify - runs| of P(t <= Tmax and r <= Rmax): " << worst << " at " << worst_t << " s, " << worst_r << " m");
  CHECK(worst < 0.17);
}

namespace {

std::string mixed_data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/data/accuracy/mixed_speeds/" + name;
}

/// Largest |verify - runs| of P(every robot within Rmax) over 0.50-0.67 m, for
/// `mission` of tests/data/accuracy/mixed_speeds (its world and models), and
/// the runs' spread of the scout's distance (q90 - q10).
std::pair<double, double> radius_error_against_runs(const std::string& mission) {
  const auto s = p3at::test::run_command(vipars() + " simulate " + mission + " --world " + mixed_data("world.yaml") +
                                         " --runs 400 --seed 5 --json");
  REQUIRE(s.status == 0);
  const nlohmann::json simulated = nlohmann::json::parse(s.out);
  std::vector<double> every, scout;  // per run: the larger of the robots' distances; the scout's
  for (const nlohmann::json& run : simulated.at("runs")) {
    if (run.at("outcome") != "success") continue;
    double worst = 0.0;
    for (const nlohmann::json& r : run.at("robots")) worst = std::max(worst, r.at("dist_to_goal_m").get<double>());
    every.push_back(worst);
    scout.push_back(run.at("robots").at(0).at("dist_to_goal_m").get<double>());
  }
  REQUIRE(every.size() > 390);
  std::sort(every.begin(), every.end());
  std::sort(scout.begin(), scout.end());

  const auto v = p3at::test::run_command(vipars() + " verify " + mission + " --models " + mixed_data("models.yaml") +
                                         " --rmax-range 0.50:0.67:0.01 --json");
  REQUIRE(!v.out.empty());
  return {radius_gap(nlohmann::json::parse(v.out), every).worst, scout[scout.size() * 9 / 10] - scout[scout.size() / 10]};
}

}  // namespace

TEST_CASE("a fast robot that turns or reports on arrival: each path runs out its own braking through the Spin or Notify") {
  // tests/data/accuracy/mixed_speeds: the scout's 18 m lane at 0.6 m/s with
  // NOISE held for the whole leg ends in a Spin (mission.yaml) or a Notify
  // and a Stop (variants/report_on_arrival.yaml). A path NOISE pushes toward
  // the goal fires faster and brakes further: the distance at rest has two
  // humps 5 cm apart. Before, only a Stop or a final state counted as braking
  // to rest, so these paths all braked like the mean, and verify's curve was
  // narrower than the runs': against these 400 runs 0.175 off for either,
  // now 0.065 (at 0.57 m, where the runs' curve is at 0.39).
  for (const std::string mission : {"mission.yaml", "variants/report_on_arrival.yaml"}) {
    // (named copies, not a structured binding: INFO's lambda captures them,
    // which clang 14 does not allow for bindings)
    const std::pair<double, double> result = radius_error_against_runs(mixed_data(mission));
    const double worst = result.first, spread = result.second;
    INFO(mission << ": largest |verify - runs| of P(r <= Rmax) " << worst << ", scout's q90 - q10 " << spread << " m");
    CHECK(spread > 0.06);  // the spread this test is about is there in the runs
    // 400 runs' own error is about 0.025 (1 sd) at the curve's middle.
    CHECK(worst < 0.1);
  }
}
