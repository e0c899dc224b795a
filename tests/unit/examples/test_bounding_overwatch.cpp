// The shipped example missions, run in fast time through team_sim::TeamScenario
// (the real executive of every robot against the simulated world and radio).
//
// Bounding Overwatch (docs/bounding-overwatch.md): over a fixed set of seeded
// runs every run must succeed and the five probabilities that summarise the
// seed paper's 100 real trials must hold, each target widened by kZ standard
// errors of a proportion estimated from that many runs. The relay example must
// succeed too.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/team_run.hpp"

namespace {

using p3at::team_sim::RunResult;
using p3at::team_sim::TeamScenario;

// The full campaign takes a few seconds in an optimised build; under ASan and
// UBSan each run is several times slower, so fewer runs (and so, through
// margin(), proportionally wider acceptance bands) keep the test short there.
#ifdef P3AT_SANITIZE_BUILD
constexpr std::size_t kRuns = 120;
#else
constexpr std::size_t kRuns = 300;
#endif
constexpr std::uint64_t kFirstSeed = 1;  // run i uses seed kFirstSeed + i, as `vipars simulate`

// A target is a bound on a true probability; the test sees an estimate p̂ from
// n independent runs, whose standard error at the bound p is sqrt(p(1-p)/n).
// Widening every bound by 3 standard errors means a design whose true
// probability sits exactly on the bound still passes with probability
// >= 99.87 % (one-sided, normal approximation), so a failure says the outcome
// has really moved, not that the fixed seeds were unlucky.
constexpr double kZ = 3.0;

double margin(double bound, std::size_t n) {
  return kZ * std::sqrt(bound * (1.0 - bound) / static_cast<double>(n));
}

std::string example_path(const std::string& relative) {
  return std::string(P3AT_SOURCE_DIR) + "/examples/" + relative;
}

TeamScenario load_example(const std::string& name) {
  return TeamScenario(p3at::mission::load_mission_file(example_path(name + "/mission.yaml")),
                      p3at::sim::load_world_file(example_path(name + "/world.yaml")));
}

struct Campaign {
  std::vector<RunResult> runs;
  std::vector<p3at::mission::Point2> goals;

  // Fraction of runs for which `pred` holds.
  template <class Pred>
  double fraction(Pred pred) const {
    std::size_t count = 0;
    for (const auto& r : runs) count += pred(r) ? 1U : 0U;
    return static_cast<double>(count) / static_cast<double>(runs.size());
  }
};

// The Bounding Overwatch campaign, run once and shared by the test cases.
const Campaign& bounding_overwatch_campaign() {
  static const Campaign campaign = [] {
    const TeamScenario scenario = load_example("bounding_overwatch");
    Campaign c;
    c.goals = scenario.goals();
    c.runs.reserve(kRuns);
    for (std::size_t i = 0; i < kRuns; ++i) c.runs.push_back(scenario.run(i, kFirstSeed + i));
    return c;
  }();
  return campaign;
}

bool both_within(const RunResult& r, double radius_m) {
  return r.robots.at(0).dist_to_goal_m <= radius_m && r.robots.at(1).dist_to_goal_m <= radius_m;
}

}  // namespace

TEST_CASE("bounding overwatch: the example is the seed paper's mission") {
  const TeamScenario scenario = load_example("bounding_overwatch");
  const auto& m = scenario.mission();
  REQUIRE(m.robots.size() == 2);
  CHECK(m.robots[0].name == "robot1");
  CHECK(m.robots[1].name == "robot2");
  CHECK(m.robots[0].start.x_m == 5.5);
  CHECK(m.robots[0].start.y_m == 5.0);
  CHECK(m.robots[1].start.x_m == 6.5);
  CHECK(m.robots[1].start.y_m == 5.0);
  CHECK(m.robots[0].max_speed_mps == 0.3);
  CHECK(m.robots[1].max_speed_mps == 0.3);
  CHECK(m.criteria.tmax_s == 200.0);
  CHECK(m.criteria.rmax_m == 2.0);
  // The goals the runner measures against are the paper's.
  REQUIRE(scenario.goals().size() == 2);
  CHECK(scenario.goals()[0].x_m == 19.75);
  CHECK(scenario.goals()[0].y_m == 18.0);
  CHECK(scenario.goals()[1].x_m == 20.0);
  CHECK(scenario.goals()[1].y_m == 17.5);
  CHECK(scenario.goals()[0] == m.robots[0].goal);  // the mission's declared goals agree
  CHECK(scenario.goals()[1] == m.robots[1].goal);
}

TEST_CASE("bounding overwatch: every run succeeds, the robots never touch, and believe they arrived") {
  const Campaign& c = bounding_overwatch_campaign();
  REQUIRE(c.runs.size() == kRuns);
  std::size_t failures = 0;
  for (const auto& r : c.runs) {
    INFO("run " << r.run << " seed " << r.seed << ": " << r.outcome);
    if (!r.success()) ++failures;
    CHECK(r.success());
    // They start 1.0 m apart (centre to centre) and only ever bound past each
    // other in lanes 2 m apart.
    CHECK(r.closest_approach_m >= 0.99);
    for (std::size_t k = 0; k < r.robots.size(); ++k) {
      // AtGoal is judged on odometry (radius 0.3 m, plus the stop's slide): the
      // 2 m the robots really miss by is the world's dead-reckoning error.
      const double believed_m =
          std::hypot(r.robots[k].odom_x_m - c.goals[k].x_m, r.robots[k].odom_y_m - c.goals[k].y_m);
      CHECK(believed_m <= 0.4);
    }
  }
  CHECK(failures == 0);
}

TEST_CASE("bounding overwatch: the outcome resembles the paper's 100 real trials") {
  const Campaign& c = bounding_overwatch_campaign();
  const std::size_t n = c.runs.size();
  const double p_t180 = c.fraction([](const RunResult& r) { return r.time_s <= 180.0; });
  const double p_t200 = c.fraction([](const RunResult& r) { return r.time_s <= 200.0; });
  const double p_t225 = c.fraction([](const RunResult& r) { return r.time_s <= 225.0; });
  const double p_r15 = c.fraction([](const RunResult& r) { return both_within(r, 1.5); });
  const double p_r25 = c.fraction([](const RunResult& r) { return both_within(r, 2.5); });
  MESSAGE("[unit_examples] bounding_overwatch runs=" << n << " p_t180=" << p_t180 << " p_t200=" << p_t200
                                                     << " p_t225=" << p_t225 << " p_r15=" << p_r15 << " p_r25=" << p_r25);

  // Targets (docs/bounding-overwatch.md), widened by margin() for n runs.
  CHECK(p_t180 <= 0.05 + margin(0.05, n));
  CHECK(p_t200 >= 0.80 - margin(0.80, n));
  CHECK(p_t200 <= 0.95 + margin(0.95, n));
  CHECK(p_t225 >= 0.97 - margin(0.97, n));
  CHECK(p_r15 <= 0.10 + margin(0.10, n));
  CHECK(p_r25 >= 0.95 - margin(0.95, n));
}

TEST_CASE("bounding overwatch: the same seed gives the same run, another seed another") {
  const TeamScenario scenario = load_example("bounding_overwatch");
  const RunResult a = scenario.run(0, 42);
  const RunResult b = scenario.run(0, 42);
  const RunResult other = scenario.run(0, 43);
  REQUIRE(a.robots.size() == 2);
  REQUIRE(b.robots.size() == 2);
  REQUIRE(other.robots.size() == 2);
  CHECK(a.outcome == b.outcome);
  CHECK(a.time_s == b.time_s);
  CHECK(a.cycles == b.cycles);
  CHECK(a.closest_approach_m == b.closest_approach_m);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(a.robots[k].end_time_s == b.robots[k].end_time_s);
    CHECK(a.robots[k].true_x_m == b.robots[k].true_x_m);
    CHECK(a.robots[k].true_y_m == b.robots[k].true_y_m);
    CHECK(a.robots[k].odom_x_m == b.robots[k].odom_x_m);
    CHECK(a.robots[k].odom_y_m == b.robots[k].odom_y_m);
  }
  // The seed reaches the noise schema and the odometry errors: a different one
  // ends the robots elsewhere.
  CHECK(other.robots[1].true_x_m != a.robots[1].true_x_m);
  // The campaign's run 41 (seed 42) is this very run.
  if (kRuns > 41) {
    const RunResult& in_campaign = bounding_overwatch_campaign().runs[41];
    CHECK(in_campaign.time_s == a.time_s);
    CHECK(in_campaign.robots[0].true_x_m == a.robots[0].true_x_m);
  }
}

TEST_CASE("relay: the example succeeds within its criteria") {
  const TeamScenario scenario = load_example("relay");
  const auto& criteria = scenario.mission().criteria;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const RunResult r = scenario.run(seed - 1, seed);
    INFO("seed " << seed << ": " << r.outcome << " t=" << r.time_s);
    CHECK(r.success());
    CHECK(r.time_s <= criteria.tmax_s);
    for (const auto& robot : r.robots) CHECK(robot.dist_to_goal_m <= criteria.rmax_m);
  }
}
