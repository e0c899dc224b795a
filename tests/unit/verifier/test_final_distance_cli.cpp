// A robot's final distance to its goal, level and spread, as `vipars verify
// --json` predicts it (dist_mean_m, dist_sd_m) against the runs of `vipars
// simulate`: on tests/data/final_distance/wall_feedback, a leg on open floor
// (right) and the same leg past two walls (a known gap, on the side that
// refuses); on tests/data/final_distance/recall_pinned (gen_7026), a robot a
// message recalls mid-leg while a strong NOISE pins some of its directions;
// on tests/data/final_distance/recall_at_start (gen_7093), a robot recalled
// within a second of starting, whose recall's places merge into one branch;
// on tests/data/final_distance/recall_redrawn (gen_7038), a robot recalled
// under a NOISE redrawn every cycle; on tests/data/final_distance/
// arc_after_noise (gen_7370), a leg without NOISE entered from the places a
// redrawn NOISE left the robot in. About 4 s.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

std::string vipars() { return p3at::test::vipars_binary(); }

/// A file of the test folder tests/data/final_distance/<folder>.
std::string data(const std::string& folder, const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/data/final_distance/" + folder + "/" + name;
}

struct DistanceFigures {
  double mean = 0.0, sd = 0.0;
  double p95 = 0.0;  ///< the runs' 95th percentile (runs only)
};

/// A robot's (the first by default) final distance to its goal as `vipars verify --json` predicts it.
DistanceFigures verified_distance(const std::string& folder, const std::string& models, std::size_t robot_index = 0) {
  const auto v = p3at::test::run_command(vipars() + " verify " + data(folder, "mission.yaml") + " --models " +
                                         data(folder, models) + " --json");
  REQUIRE(!v.out.empty());
  const nlohmann::json robot = nlohmann::json::parse(v.out).at("robots").at(robot_index);
  return {robot.at("dist_mean_m").get<double>(), robot.at("dist_sd_m").get<double>()};
}

/// The same over `runs` runs of `vipars simulate` (seed `seed`).
DistanceFigures simulated_distance(const std::string& folder, const std::string& world, int runs, int seed,
                                   std::size_t robot_index = 0) {
  const auto s = p3at::test::run_command(vipars() + " simulate " + data(folder, "mission.yaml") + " --world " +
                                         data(folder, world) + " --runs " + std::to_string(runs) + " --seed " +
                                         std::to_string(seed) + " --json");
  REQUIRE(s.status == 0);
  std::vector<double> d;
  const nlohmann::json simulated = nlohmann::json::parse(s.out);
  for (const nlohmann::json& run : simulated.at("runs")) {
    d.push_back(run.at("robots").at(robot_index).at("dist_to_goal_m").get<double>());
  }
  REQUIRE(!d.empty());
  double sum = 0.0, squares = 0.0;
  for (const double x : d) sum += x;
  const double mean = sum / static_cast<double>(d.size());
  for (const double x : d) squares += (x - mean) * (x - mean);
  std::sort(d.begin(), d.end());
  return {mean, std::sqrt(squares / static_cast<double>(d.size())), d[d.size() * 95 / 100]};
}

enum class Spread { checked, not_checked };

/// A robot's final distance as verify predicts it against 400 runs (seed 3):
/// the means within `mean_tolerance` metres and, when checked, the spreads
/// within a third of each other.
void check_against_runs(const std::string& folder, std::size_t robot_index, double mean_tolerance, Spread spread) {
  const DistanceFigures verified = verified_distance(folder, "models.yaml", robot_index);
  const DistanceFigures runs = simulated_distance(folder, "world.yaml", 400, 3, robot_index);
  INFO(folder << ", robot " << robot_index + 1 << ": verify " << verified.mean << " ± " << verified.sd
              << " m, 400 runs " << runs.mean << " ± " << runs.sd << " m");
  CHECK(std::abs(verified.mean - runs.mean) < mean_tolerance);
  if (spread == Spread::checked) {
    CHECK(verified.sd / runs.sd > 0.75);
    CHECK(verified.sd / runs.sd < 1.33);
  }
}

}  // namespace

TEST_CASE("the final distance's spread (dist_sd_m): right on open floor; beside walls wider than the runs', never narrower") {
  // Open floor: the odometry's error alone spreads the distance, and the
  // verifier's error model is that spread (16.6 mm against 16.5 mm).
  const DistanceFigures open = verified_distance("wall_feedback", "models_open.yaml");
  const DistanceFigures open_runs = simulated_distance("wall_feedback", "world_open.yaml", 1000, 1);
  INFO("open floor: verify " << open.mean << " ± " << open.sd << " m, 1,000 runs " << open_runs.mean << " ± "
                             << open_runs.sd << " m");
  CHECK(std::abs(open.mean - open_runs.mean) < 0.005);
  CHECK(open.sd == doctest::Approx(open_runs.sd).epsilon(0.15));

  // Beside the two walls the sonar, which sees them from the true pose, makes
  // the odometric path answer the error, and the runs' distance spreads 2.4
  // times less (6.4 mm) than the open-loop error model says (15.2 mm): a known
  // gap (docs/verifier.md). It must stay on the side that refuses rather than
  // launches: the mean right, the spread not narrower than the runs', so that
  // at the runs' 95th percentile the verifier's P(within) is not above 0.95.
  const DistanceFigures walls = verified_distance("wall_feedback", "models.yaml");
  const DistanceFigures wall_runs = simulated_distance("wall_feedback", "world.yaml", 1000, 1);
  INFO("beside the walls: verify " << walls.mean << " ± " << walls.sd << " m, 1,000 runs " << wall_runs.mean << " ± "
                                   << wall_runs.sd << " m (95th percentile " << wall_runs.p95 << " m)");
  CHECK(std::abs(walls.mean - wall_runs.mean) < 0.005);
  CHECK(walls.sd >= wall_runs.sd);
  const auto at_p95 = p3at::test::run_command(vipars() + " verify " + data("wall_feedback", "mission.yaml") +
                                              " --models " + data("wall_feedback", "models.yaml") + " --rmax " +
                                              std::to_string(wall_runs.p95) + " --json");
  CHECK(nlohmann::json::parse(at_p95.out).at("p_radius").get<double>() <= 0.95 + 0.01);
}

TEST_CASE("a robot recalled mid-leg while a strong NOISE pins some directions: where the recall finds it") {
  // gen_7026's robot1: five of its eight held NOISE directions pin it against
  // the walls for good, but the NOISE is redrawn every 118 cycles, which frees
  // nearly every run; robot2's message recalls it about 4.5 s into its leg.
  // Where the recall finds it is where all eight directions have got to, not
  // only the three that got through on their first draw: with those alone
  // verify put it 9 cm too far along (7.264 m from its goal against the runs'
  // 7.359 m) with a third of their spread (0.029 m against 0.090 m).
  check_against_runs("recall_pinned", 0, 0.04, Spread::checked);  // the runs' mean is known to ±0.005 m
}

TEST_CASE("a robot recalled within a second of starting: its recall's places merged into one branch keep their mean and spread") {
  // gen_7093's robot1 (its last leg shortened) is recalled 0.1 to 1.1 s into
  // its first leg (the recall's bins put it 2 mm to 0.25 m along), and its
  // next event merges the bins into one branch. Keeping the first bin's
  // place there put it 1.798 m from its goal with a spread of 0.8 mm, where
  // 400 runs end 1.750 m from it with a spread of 54 mm; robot2, whose
  // interruption's bins merge the same way, was 27 mm too far.
  check_against_runs("recall_at_start", 0, 0.015, Spread::checked);  // the runs' mean is known to ±0.003 m
  // robot2's spread at its recall lies across the way to its last goal, so
  // it moves the distance only at second order: its mean is the check.
  check_against_runs("recall_at_start", 1, 0.015, Spread::not_checked);
}

TEST_CASE("a robot recalled mid-leg under a NOISE redrawn every cycle: the held paths at the redrawn pace and spread") {
  // gen_7038's robot3 (NOISE gain 0.255 redrawn every cycle, recalled about
  // 10.3 s into an 8 m leg). Read at their own time, the held paths put it
  // 0.10 m farther along than the runs (5.187 m from its goal against
  // 5.288 m), and the held directions, each pushing its path aside for the
  // whole leg, fanned out three times wider than a NOISE that keeps turning
  // (0.288 m against 0.088 m): read at the redrawn pace and brought to the
  // redrawn spread (engine/trajectory_pace.hpp).
  check_against_runs("recall_redrawn", 2, 0.03, Spread::checked);  // the runs' mean is known to ±0.005 m
}

TEST_CASE("a leg without NOISE entered from several places: its ends keep their arc around the goal") {
  // gen_7370's robot1: leg1's redrawn NOISE leaves it anywhere on its AtGoal
  // circle, and leg2 (no NOISE) drives from each of those places to about
  // 0.25 m short of its goal, so the ends lie on an arc at nearly one
  // distance. One slab for the leg made them one Gaussian blob: verify said
  // 0.249 +- 0.043 m where the runs end 0.253 +- 0.012 m.
  check_against_runs("arc_after_noise", 0, 0.01, Spread::checked);
  // The arc is why: the final position spreads by 0.1 m across the way in,
  // and a blob that wide would spread the distance by about 0.04 m.
  const auto v = p3at::test::run_command(vipars() + " verify " + data("arc_after_noise", "mission.yaml") + " --models " +
                                         data("arc_after_noise", "models.yaml") + " --json");
  const nlohmann::json robot = nlohmann::json::parse(v.out).at("robots").at(0);
  CHECK(robot.at("final_sd_m").get<double>() > 0.08);
  CHECK(robot.at("dist_sd_m").get<double>() < 0.02);
}
