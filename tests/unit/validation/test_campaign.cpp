// The parallel campaign runner: run i's seed depends on (campaign seed, i)
// only, results come back by index, so any number of threads gives the same
// campaign; failed runs are kept; a run that throws stops the campaign. And
// what a finished run records: each robot's poses where it came to rest.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/team_sim/run_table.hpp"

namespace {

using p3at::team_sim::CampaignOptions;
using p3at::team_sim::RunResult;
using p3at::team_sim::TeamScenario;

std::string example(const std::string& relative) { return std::string(P3AT_SOURCE_DIR) + "/examples/" + relative; }

TeamScenario relay() {
  return TeamScenario(p3at::mission::load_mission_file(example("relay/mission.yaml")),
                      p3at::sim::load_world_file(example("relay/world.yaml")));
}

// Everything a run reports except the executive's measured compute time.
void check_same_run(const RunResult& a, const RunResult& b) {
  CHECK(p3at::team_sim::csv_row(a) == p3at::team_sim::csv_row(b));
  CHECK(a.run == b.run);
  CHECK(a.seed == b.seed);
  CHECK(a.outcome == b.outcome);
  CHECK(a.time_s == b.time_s);
  CHECK(a.cycles == b.cycles);
  CHECK(a.closest_approach_m == b.closest_approach_m);
  REQUIRE(a.robots.size() == b.robots.size());
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    CHECK(a.robots[i].phase == b.robots[i].phase);
    CHECK(a.robots[i].end_time_s == b.robots[i].end_time_s);
    CHECK(a.robots[i].true_x_m == b.robots[i].true_x_m);
    CHECK(a.robots[i].true_y_m == b.robots[i].true_y_m);
    CHECK(a.robots[i].odom_x_m == b.robots[i].odom_x_m);
    CHECK(a.robots[i].dist_to_goal_m == b.robots[i].dist_to_goal_m);
  }
}

}  // namespace

TEST_CASE("run seeds are SplitMix64's outputs (reference vectors)") {
  // Vigna's splitmix64.c seeded with 1234567: its first five outputs.
  const std::uint64_t expected[] = {6457827717110365317ULL, 3203168211198807973ULL, 9817491932198370423ULL,
                                    4593380528125082431ULL, 16408922859458223821ULL};
  for (std::uint64_t i = 0; i < 5; ++i) CHECK(p3at::team_sim::run_seed(1234567, i) == expected[i]);
  CHECK(p3at::team_sim::run_seed(0, 0) == 0xE220A8397B1DCDAFULL);
  // Nearby campaign seeds share no run seeds (unlike seed + i).
  CHECK(p3at::team_sim::run_seed(1, 1) != p3at::team_sim::run_seed(2, 0));
}

TEST_CASE("campaign_jobs: default, explicit, never more threads than runs") {
  CampaignOptions o;
  o.runs = 100;
  o.jobs = 3;
  CHECK(p3at::team_sim::campaign_jobs(o) == 3);
  o.jobs = 0;
  CHECK(p3at::team_sim::campaign_jobs(o) >= 1);
  o.runs = 2;
  o.jobs = 8;
  CHECK(p3at::team_sim::campaign_jobs(o) == 2);
  o.runs = 0;
  CHECK(p3at::team_sim::campaign_jobs(o) == 1);
}

TEST_CASE("the same campaign on 1 and 3 threads, run by run; and each run replays alone") {
  const TeamScenario scenario = relay();
  CampaignOptions o;
  o.runs = 10;
  o.seed = 77;
  o.jobs = 1;
  const auto one = p3at::team_sim::run_campaign(scenario, o);
  o.jobs = 3;
  std::vector<std::uint64_t> progress;
  const auto three = p3at::team_sim::run_campaign(
      scenario, o, [&progress](std::uint64_t done, std::uint64_t total) {
        CHECK(total == 10);
        progress.push_back(done);
      });
  REQUIRE(one.size() == 10);
  REQUIRE(three.size() == 10);
  for (std::size_t i = 0; i < one.size(); ++i) {
    CAPTURE(i);
    CHECK(one[i].run == i);
    CHECK(one[i].seed == p3at::team_sim::run_seed(77, i));
    CHECK(one[i].success());
    check_same_run(one[i], three[i]);
  }
  // Progress only grows and ends with every run done.
  REQUIRE_FALSE(progress.empty());
  CHECK(progress.back() == 10);
  for (std::size_t i = 1; i < progress.size(); ++i) CHECK(progress[i - 1] <= progress[i]);
  // Run 7 alone, from its seed, is run 7 of the campaign.
  check_same_run(scenario.run(7, p3at::team_sim::run_seed(77, 7)), one[7]);
  // Another campaign seed gives other runs.
  o.seed = 78;
  const auto other = p3at::team_sim::run_campaign(scenario, o);
  CHECK(other[0].seed != one[0].seed);
  CHECK(p3at::team_sim::csv_row(other[0]) != p3at::team_sim::csv_row(one[0]));
}

TEST_CASE("runs that time out are kept and counted as failed") {
  const TeamScenario scenario = relay();
  CampaignOptions o;
  o.runs = 4;
  o.jobs = 2;
  o.run.timeout_s = 3.0;  // robot1 needs about 7 s for its 2 m, robot2 has not started
  const auto runs = p3at::team_sim::run_campaign(scenario, o);
  REQUIRE(runs.size() == 4);
  // The reason, without --verbose: who is still running, in which state, why.
  for (const auto& r : runs) {
    CHECK(r.outcome == "timeout (robot1 in 'drive' still moving; robot2 in 'wait' waiting for 'r1_done' from robot1)");
  }
  const auto p = p3at::team_sim::empirical_at(runs, 1000.0, 100.0);
  CHECK(p.runs == 4);
  CHECK(p.failed_runs == 4);
  CHECK(p.time.count == 0);    // a failed run never meets the time bound...
  CHECK(p.radius.count == 4);  // ...but its true distances still count
  CHECK(p.joint.count == 0);
  REQUIRE(p.robots.size() == 2);
  // robot2 never moved: still its 2 m from its goal.
  CHECK(p.robots[1].dist_mean_m == doctest::Approx(2.0).epsilon(0.02));
  CHECK(p.robots[0].dist_mean_m < 1.9);
}

TEST_CASE("a finished run records each robot where it came to rest, past where its final AtGoal fired") {
  // tests/data/run_out: one robot still at 0.5 m/s when AtGoal fires 0.3 m
  // short of its goal (dropoff 0.3 m); its final Stop brakes it at the
  // simulated P3-AT's 0.6 m/s^2, 0.5^2 / 1.2 = 0.208 m (0.206 m in the
  // firmware's 10 ms ramp steps) further along its heading.
  const std::string dir = std::string(P3AT_SOURCE_DIR) + "/tests/data/run_out/";
  const TeamScenario scenario(p3at::mission::load_mission_file(dir + "mission.yaml"),
                              p3at::sim::load_world_file(dir + "world.yaml"));
  const double heading = 30.0 * 3.14159265358979323846 / 180.0;
  p3at::team_sim::RunOptions at_firing;
  at_firing.rest_s = 0.0;  // ends at the cycle the last robot finished: where AtGoal fired
  p3at::team_sim::RunOptions cut_short;
  cut_short.rest_s = 0.5;  // the braking takes 0.84 s: the bound stops it part-way
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    CAPTURE(seed);
    const RunResult fired = scenario.run(0, seed, at_firing);
    const RunResult rest = scenario.run(0, seed);
    const RunResult part = scenario.run(0, seed, cut_short);
    REQUIRE(fired.success());
    REQUIRE(rest.success());
    REQUIRE(part.success());
    // The completion time is when the robot entered its final state, however long it then brakes.
    CHECK(rest.time_s == fired.time_s);
    CHECK(part.time_s == fired.time_s);
    CHECK(rest.robots[0].end_time_s == fired.robots[0].end_time_s);
    CHECK(rest.cycles > part.cycles);
    CHECK(part.cycles > fired.cycles);
    const auto& f = fired.robots[0];
    const auto& r = rest.robots[0];
    // Fired within the radius, at rest past it, along the heading by the whole braking distance.
    CHECK(std::hypot(f.odom_x_m - 5.4641, f.odom_y_m - 4.0) <= 0.3);
    const double along = (r.true_x_m - f.true_x_m) * std::cos(heading) + (r.true_y_m - f.true_y_m) * std::sin(heading);
    const double across = -(r.true_x_m - f.true_x_m) * std::sin(heading) + (r.true_y_m - f.true_y_m) * std::cos(heading);
    CHECK(along == doctest::Approx(0.206).epsilon(0.01));
    CHECK(std::abs(across) < 0.002);
    // Braking straight on: the heading it rests with is the one it fired with (degrees, true and odometric).
    CHECK(std::abs(r.true_theta_deg - f.true_theta_deg) < 0.5);
    CHECK(std::abs(r.true_theta_deg - heading * 180.0 / 3.14159265358979323846) < 5.0);
    CHECK(std::abs(r.odom_theta_deg - r.true_theta_deg) < 5.0);
    const double odom_along = std::hypot(r.odom_x_m - f.odom_x_m, r.odom_y_m - f.odom_y_m);
    CHECK(odom_along == doctest::Approx(0.206).epsilon(0.03));  // odometry counts it, with its random error
    CHECK(r.dist_to_goal_m < f.dist_to_goal_m - 0.15);
    // Cut short by the bound: part of the way.
    const double part_along = std::hypot(part.robots[0].true_x_m - f.true_x_m, part.robots[0].true_y_m - f.true_y_m);
    CHECK(part_along > 0.1);
    CHECK(part_along < along - 0.03);
  }
  // Never past the run's timeout: a timeout 0.3 s after the firing stops the braking there, the run still a success.
  const RunResult fired = scenario.run(0, 1, at_firing);
  p3at::team_sim::RunOptions tight;
  tight.timeout_s = fired.time_s + 0.1 + 0.3;  // the executive's clock starts at the first cycle, 0.1 s in
  const RunResult stopped = scenario.run(0, 1, tight);
  CHECK(stopped.success());
  CHECK(stopped.time_s == fired.time_s);
  const double stopped_along =
      std::hypot(stopped.robots[0].true_x_m - fired.robots[0].true_x_m, stopped.robots[0].true_y_m - fired.robots[0].true_y_m);
  CHECK(stopped_along > 0.05);
  CHECK(stopped_along < 0.18);
}

TEST_CASE("a run that throws stops the campaign and the error reaches the caller") {
  auto world = p3at::sim::load_world_file(example("relay/world.yaml"));
  world.radio.loss_probability = 2.0;  // the radio cannot be built: every run throws
  const TeamScenario scenario(p3at::mission::load_mission_file(example("relay/mission.yaml")), world);
  CampaignOptions o;
  o.runs = 50;
  o.jobs = 3;
  CHECK_THROWS_AS(p3at::team_sim::run_campaign(scenario, o), std::invalid_argument);
}
