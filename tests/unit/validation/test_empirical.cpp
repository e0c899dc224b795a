// Empirical probabilities over a hand-made set of runs whose answers were
// worked out by hand, including failed runs (a timeout, an abort) that must
// be counted, never dropped; and the grid against the single-point figures.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "p3at/team_sim/empirical.hpp"
#include "p3at/team_sim/wilson.hpp"

namespace {

using p3at::team_sim::Estimate;
using p3at::team_sim::RunResult;

RunResult make_run(std::uint64_t index, const std::string& outcome, double time_s, double r1, double r2) {
  RunResult run;
  run.run = index;
  run.seed = 100 + index;
  run.outcome = outcome;
  run.time_s = time_s;
  for (auto [name, d] : {std::pair{"robot1", r1}, std::pair{"robot2", r2}}) {
    p3at::team_sim::RobotResult r;
    r.name = name;
    r.dist_to_goal_m = d;
    run.robots.push_back(r);
  }
  return run;
}

// t, r1, r2 per run; worst distance in the comment.
std::vector<RunResult> hand_runs() {
  return {
      make_run(0, "success", 190.0, 1.0, 1.5),                    // worst 1.5
      make_run(1, "success", 200.0, 2.0, 1.0),                    // worst 2.0
      make_run(2, "success", 210.0, 0.5, 0.5),                    // worst 0.5
      make_run(3, "timeout", 900.0, 3.0, 0.2),                    // t = inf, worst 3.0
      make_run(4, "aborted (robot2: stuck)", 50.0, 0.1, 0.1),     // t = inf although 50 s, worst 0.1
  };
}

void check_estimate(const Estimate& e, std::uint64_t count, std::uint64_t runs) {
  CHECK(e.count == count);
  CHECK(e.runs == runs);
  CHECK(e.p == doctest::Approx(static_cast<double>(count) / static_cast<double>(runs)));
  const auto ci = p3at::team_sim::wilson_interval(count, runs);
  CHECK(e.ci_low == ci.low);
  CHECK(e.ci_high == ci.high);
}

}  // namespace

TEST_CASE("failed runs never meet the time bound but keep their true distances") {
  const auto runs = hand_runs();
  CHECK(std::isinf(p3at::team_sim::completion_time_s(runs[3])));
  CHECK(std::isinf(p3at::team_sim::completion_time_s(runs[4])));
  CHECK(p3at::team_sim::completion_time_s(runs[0]) == 190.0);
  CHECK(p3at::team_sim::worst_distance_m(runs[3]) == 3.0);
}

TEST_CASE("empirical_at: hand-computed figures at (200 s, 2.0 m)") {
  const auto p = p3at::team_sim::empirical_at(hand_runs(), 200.0, 2.0);
  CHECK(p.tmax_s == 200.0);
  CHECK(p.rmax_m == 2.0);
  CHECK(p.runs == 5);
  CHECK(p.failed_runs == 2);
  check_estimate(p.time, 2, 5);    // runs 0, 1 (run 4's 50 s does not count: it failed)
  check_estimate(p.radius, 4, 5);  // all but run 3
  check_estimate(p.joint, 2, 5);   // runs 0, 1
  REQUIRE(p.robots.size() == 2);
  CHECK(p.robots[0].name == "robot1");
  check_estimate(p.robots[0].radius, 4, 5);  // 3.0 > 2.0
  check_estimate(p.robots[1].radius, 5, 5);
  // Distances over all five runs: robot1 1, 2, 0.5, 3, 0.1: mean 1.32,
  // sample variance (0.1024 + 0.4624 + 0.6724 + 2.8224 + 1.4884) / 4 = 1.387.
  CHECK(p.robots[0].dist_mean_m == doctest::Approx(1.32));
  CHECK(p.robots[0].dist_sd_m == doctest::Approx(std::sqrt(1.387)));
  // Completion time over the successful runs only: 190, 200, 210.
  REQUIRE(p.completion_mean_s.has_value());
  CHECK(*p.completion_mean_s == doctest::Approx(200.0));
  CHECK(*p.completion_sd_s == doctest::Approx(10.0));
}

TEST_CASE("empirical_grid: hand-computed grid, failed runs in the denominator") {
  const auto runs = hand_runs();
  const std::vector<double> tmax{195.0, 200.0, 1000.0};
  const std::vector<double> rmax{0.3, 1.5, 2.5, 5.0};
  const auto g = p3at::team_sim::empirical_grid(runs, tmax, rmax);
  CHECK(g.tmax == tmax);
  CHECK(g.rmax == rmax);
  REQUIRE(g.time.size() == 3);
  REQUIRE(g.radius.size() == 4);
  REQUIRE(g.joint.size() == 3);
  // P(t <= T): 195: run 0; 200: runs 0, 1; 1000: runs 0-2 (the timeout's 900 s is not a completion).
  check_estimate(g.time[0], 1, 5);
  check_estimate(g.time[1], 2, 5);
  check_estimate(g.time[2], 3, 5);
  // P(worst <= R): 0.3: run 4; 1.5: runs 0, 2, 4 (1.5 <= 1.5); 2.5: + run 1; 5: all.
  check_estimate(g.radius[0], 1, 5);
  check_estimate(g.radius[1], 3, 5);
  check_estimate(g.radius[2], 4, 5);
  check_estimate(g.radius[3], 5, 5);
  const std::uint64_t joint[3][4] = {{0, 1, 1, 1}, {0, 1, 2, 2}, {0, 2, 3, 3}};
  for (std::size_t a = 0; a < 3; ++a) {
    REQUIRE(g.joint[a].size() == 4);
    for (std::size_t b = 0; b < 4; ++b) {
      CAPTURE(a);
      CAPTURE(b);
      check_estimate(g.joint[a][b], joint[a][b], 5);
    }
  }
}

TEST_CASE("empirical_grid agrees with empirical_at in every cell, axes in any order") {
  // A larger pseudo-random set (fixed LCG), with some failures.
  std::vector<RunResult> runs;
  std::uint64_t state = 12345;
  const auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;  // [0, 1)
  };
  for (std::uint64_t i = 0; i < 400; ++i) {
    const bool failed = next() < 0.1;
    runs.push_back(make_run(i, failed ? "timeout" : "success", 180.0 + 40.0 * next(), 3.0 * next(), 3.0 * next()));
  }
  const std::vector<double> tmax{230.0, 170.0, 200.0, 185.5, 215.0};  // deliberately unsorted
  const std::vector<double> rmax{2.5, 0.5, 1.0, 3.0, 1.75};
  const auto g = p3at::team_sim::empirical_grid(runs, tmax, rmax);
  for (std::size_t a = 0; a < tmax.size(); ++a) {
    for (std::size_t b = 0; b < rmax.size(); ++b) {
      CAPTURE(tmax[a]);
      CAPTURE(rmax[b]);
      const auto p = p3at::team_sim::empirical_at(runs, tmax[a], rmax[b]);
      CHECK(g.joint[a][b].count == p.joint.count);
      CHECK(g.time[a].count == p.time.count);
      CHECK(g.radius[b].count == p.radius.count);
    }
  }
  // The probabilities grow along both axes.
  CHECK(g.joint[1][1].count <= g.joint[2][1].count);
  CHECK(g.joint[2][1].count <= g.joint[2][2].count);
  CHECK(g.joint[0][3].count > g.joint[1][1].count);
}

TEST_CASE("no runs, and no successful run") {
  const auto empty = p3at::team_sim::empirical_at({}, 200.0, 2.0);
  CHECK(empty.runs == 0);
  CHECK(empty.joint.p == 0.0);
  CHECK(empty.joint.ci_low == 0.0);
  CHECK(empty.joint.ci_high == 1.0);
  CHECK(empty.robots.empty());
  CHECK_FALSE(empty.completion_mean_s.has_value());

  const std::vector<RunResult> failed{make_run(0, "timeout", 900.0, 0.1, 0.1), make_run(1, "timeout", 900.0, 0.2, 0.1)};
  const auto p = p3at::team_sim::empirical_at(failed, 1e9, 2.0);
  CHECK(p.failed_runs == 2);
  CHECK(p.time.count == 0);
  CHECK(p.radius.count == 2);
  CHECK(p.joint.count == 0);
  CHECK_FALSE(p.completion_mean_s.has_value());
}

TEST_CASE("regions by the joint probability") {
  using p3at::team_sim::classify;
  using p3at::team_sim::Region;
  CHECK(classify(0.0, 0.05, 0.95) == Region::unsuccessful);
  CHECK(classify(0.0499, 0.05, 0.95) == Region::unsuccessful);
  CHECK(classify(0.05, 0.05, 0.95) == Region::uncertain);
  CHECK(classify(0.9499, 0.05, 0.95) == Region::uncertain);
  CHECK(classify(0.95, 0.05, 0.95) == Region::successful);
  CHECK(classify(0.5, 0.6, 0.9) == Region::unsuccessful);
  CHECK(std::string(p3at::team_sim::to_string(Region::unsuccessful)) == "unsuccessful");
  CHECK(std::string(p3at::team_sim::to_string(Region::uncertain)) == "uncertain");
  CHECK(std::string(p3at::team_sim::to_string(Region::successful)) == "successful");
}
