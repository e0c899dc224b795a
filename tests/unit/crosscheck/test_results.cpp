// The campaign's summary statistics, JSON shape and baseline check on
// hand-made mission results.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "p3at/common/number_format.hpp"
#include "p3at/crosscheck/baseline.hpp"
#include "p3at/crosscheck/result_json.hpp"
#include "p3at/crosscheck/separation_curve.hpp"
#include "scratch.hpp"

using namespace p3at::crosscheck;

namespace {

MissionResult result(const std::string& name, double time, double radius, double joint, std::size_t overconfident,
                     bool evaluable = true) {
  MissionResult r;
  r.name = name;
  r.generator_seed = 1;
  r.robots = 2;
  r.runs = 1000;
  r.evaluable = evaluable;
  r.score.time.strict = time;
  r.score.time.tolerant = time / 2;
  r.score.radius.strict = radius;
  r.score.radius.tolerant = radius / 2;
  r.score.joint.strict = joint;
  r.score.joint.tolerant = joint / 2;
  r.score.overconfident_go_cells = overconfident;
  return r;
}

}  // namespace

TEST_CASE("summary: percentiles by nearest rank, fractions within the bounds, GO cells of evaluable missions only") {
  std::vector<MissionResult> rs;
  for (int k = 1; k <= 10; ++k) rs.push_back(result("m" + std::to_string(k), 0.01 * k, 0.02, 0.03 * k, 0));
  rs[9].score.overconfident_go_cells = 7;               // evaluable
  rs[8].score.overconfident_go_cells = 4;
  rs[8].evaluable = false;                              // listed apart
  MissionResult broken;
  broken.name = "broken";
  broken.error = "world does not load";
  rs.push_back(broken);
  const CampaignSummary s = summarize(rs, Bounds{});
  CHECK(s.missions == 11);
  CHECK(s.scored == 10);
  CHECK(s.could_not_run == 1);
  CHECK(s.not_evaluable == 1);
  CHECK(s.runs == 10000);
  CHECK(s.time_strict.worst == doctest::Approx(0.10));
  CHECK(s.time_strict.p50 == doctest::Approx(0.05));
  CHECK(s.time_strict.p90 == doctest::Approx(0.09));
  CHECK(s.time_strict.p95 == doctest::Approx(0.10));
  CHECK(s.time_strict.within == 5);                     // 0.01 .. 0.05 <= 0.05
  CHECK(s.time_tolerant.within == 10);                  // halves: all <= 0.05
  CHECK(s.joint_strict.within == 2);                    // 0.03, 0.06 <= 0.08
  CHECK(s.all_within_strict == 2);
  CHECK(s.overconfident_cells == 7);
  CHECK(s.overconfident_missions == 1);
  CHECK(s.overconfident_cells_not_evaluable == 4);
  const std::string text = summary_text(s, Bounds{});
  CHECK(text.find("missions 11: scored 10") != std::string::npos);
  CHECK(text.find("7 on 1 evaluable") != std::string::npos);
}

TEST_CASE("table lines: the printf layout, and an error text of any length kept whole") {
  // The layout the tables had when they were printf'd ("%-18s %zu robot%s  time %.3f / %.3f ...").
  MissionResult r = result("gen_4", 0.02, 0.01, 0.03, 1);
  CHECK(mission_line(r, Bounds{}) ==
        "gen_4              2 robots  time 0.020 / 0.010  radius 0.010 / 0.005  joint 0.030 / 0.015  "
        "over-confident GO 1  ok");
  r.robots = 1;
  r.evaluable = false;
  r.score.time.strict = 0.0625;  // beyond the 0.05 bound, within it with the 1 % shift
  CHECK(mission_line(r, Bounds{}) ==
        "gen_4              1 robot   time 0.062 / 0.010  radius 0.010 / 0.005  joint 0.030 / 0.015  "
        "over-confident GO 1 (cannot evaluate)  ok within 1 %");

  // A could-not-run line used to be cut at 400 bytes (a fixed buffer); a
  // loader's message naming a long path is longer than that.
  MissionResult broken;
  broken.name = "gen_12";
  broken.error = "/tmp/" + std::string(500, 'd') + "/world.yaml:3:10: expected a number for 'x_m', got 'north'";
  REQUIRE(broken.error.size() > 400);
  const std::string line = mission_line(broken, Bounds{});
  CHECK(line == "gen_12             could not run: " + broken.error);
  CHECK(line.size() == 18 + 16 + broken.error.size());
  // And a name longer than its column widens it, as printf did.
  broken.name = std::string(30, 'n');
  CHECK(mission_line(broken, Bounds{}) == std::string(30, 'n') + " could not run: " + broken.error);

  std::vector<MissionResult> rs{result("a", 0.01, 0.02, 0.03, 0), result("b", 0.1, 0.02, 0.09, 2)};
  CHECK(summary_text(summarize(rs, Bounds{}), Bounds{}) ==
        "missions 2: scored 2 (of which verify cannot evaluate 0), could not run 0; 2000 validation runs\n"
        "max |verify - validate|     worst    p50    p90    p95   within bound\n"
        "time curve, strict          0.100  0.010  0.100  0.100   1 of 2 (50 %) <= 0.05\n"
        "time curve, 1 % shift       0.050  0.005  0.050  0.050   2 of 2 (100 %) <= 0.05\n"
        "radius curve, strict        0.020  0.020  0.020  0.020   2 of 2 (100 %) <= 0.05\n"
        "radius curve, 1 % shift     0.010  0.010  0.010  0.010   2 of 2 (100 %) <= 0.05\n"
        "joint surface, strict       0.090  0.030  0.090  0.090   1 of 2 (50 %) <= 0.08\n"
        "joint surface, 1 % shift    0.045  0.015  0.045  0.045   2 of 2 (100 %) <= 0.08\n"
        "all three within 0.05/0.05/0.08: strict 1 of 2 (50 %), with the 1 % shift 2 (100 %)\n"
        "over-confident GO cells (verify >= 0.8, validation's 95 % interval below 0.78): 2 on 1 evaluable "
        "missions; 0 more on missions verify cannot evaluate\n");
}

TEST_CASE("JSON: the keys a machine reads, in order") {
  MissionResult r = result("gen_4", 0.02, 0.01, 0.03, 1);
  r.approximations = {"NOISE redrawn inside a leg"};
  const auto j = mission_result_json(r);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  const std::vector<std::string> expected{"name", "source", "generator_seed", "robots", "error", "evaluable",
                                          "approximations", "calibration", "runs", "failed_runs", "tmax_range",
                                          "rmax_range", "criteria", "time", "radius", "joint",
                                          "overconfident_go_cells", "overconfident_worst", "separation",
                                          "robot_distances", "within_bounds_strict",
                                          "within_bounds_tolerant", "seconds", "folder", "reproduce"};
  CHECK(keys == expected);
  CHECK(j["time"]["strict"] == 0.02);
  CHECK(j["time"]["tolerant"] == 0.01);
  CHECK(j["time"]["strict_at"]["rmax_m"].is_null());   // NaN is not JSON: null
  CHECK(j["error"].is_null());
  CHECK(j["approximations"][0] == "NOISE redrawn inside a leg");
  CHECK(j["within_bounds_strict"] == true);
  const auto s = summary_json(summarize({r}, Bounds{}), Bounds{});
  for (const char* k : {"missions", "scored", "could_not_run", "not_evaluable", "runs", "bounds", "time", "radius", "joint",
                        "all_within_strict", "all_within_tolerant", "overconfident_go_cells", "overconfident_go_missions",
                        "overconfident_go_cells_not_evaluable"}) {
    CHECK(s.contains(k));
  }
  CHECK(s["time"]["strict"]["worst"] == 0.02);
  CHECK(s["bounds"]["joint"] == 0.08);
  CHECK(mission_line(r, Bounds{}).find("gen_4") == 0);
  CHECK(j["separation"].is_null());  // no closest-approach curve: a one-robot mission
}

TEST_CASE("the closest-approach curve: scored against the runs, kept through JSON, in the summary") {
  // Runs whose closest approach is spread evenly over [1, 2) m: P(apart > d) = 2 - d.
  std::vector<p3at::team_sim::RunResult> runs(1000);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    runs[k].robots.resize(2);
    runs[k].closest_approach_m = 1.0 + static_cast<double>(k) / 1000.0;
  }
  // A verifier sure the robots pass 1.5 m apart: a step from 1 to 0 at 1.5 m,
  // 0.5 off the runs there, and GO (>= 0.8) where the runs are clearly below.
  p3at::verifier::SystemOutcome outcome;
  p3at::verifier::Branch b;
  b.robots.resize(2);
  p3at::verifier::SeparationSample s;
  s.robot_i = 0;
  s.robot_j = 1;
  s.difference.mean = Eigen::Vector2d(1.5, 0.0);
  s.difference.cov = 1e-8 * Eigen::Matrix2d::Identity();
  s.rigid_s = 20;
  b.separations = {s};
  outcome.branches = {b};
  const auto score = score_separation(outcome, runs, 41, 0.0);
  REQUIRE(score.has_value());
  CHECK(score->error.strict == doctest::Approx(0.5).epsilon(0.05));
  CHECK(score->overconfident_points > 0);
  CHECK(score->range.find(':') != std::string::npos);
  // One robot (no pair): no curve.
  std::vector<p3at::team_sim::RunResult> alone(10);
  for (auto& r : alone) r.robots.resize(1);
  CHECK_FALSE(score_separation(outcome, alone, 41, 0.0).has_value());
  // Decided a step stricter (0.3 m: the step at 1.5 m is passed from d = 1.2
  // m), fewer points are over-confident; the raw curve's error is the same.
  const auto decided = score_separation(outcome, runs, 41, 0.3);
  REQUIRE(decided.has_value());
  CHECK(decided->overconfident_points < score->overconfident_points);
  CHECK(decided->error.strict == score->error.strict);

  MissionResult r = result("gen_9", 0.02, 0.01, 0.03, 0);
  r.separation = score;
  const MissionResult back = mission_result_from_json(nlohmann::json::parse(mission_result_json(r).dump()));
  REQUIRE(back.separation.has_value());
  CHECK(back.separation->error.strict == r.separation->error.strict);
  CHECK(back.separation->overconfident_points == r.separation->overconfident_points);
  CHECK(back.separation->range == r.separation->range);
  CHECK(mission_line(r, Bounds{}).find("apart " + p3at::format_fixed(r.separation->error.strict, 3)) != std::string::npos);
  const std::string text = summary_text(summarize({r}, Bounds{}), Bounds{});
  CHECK(text.find("separation curve, strict") != std::string::npos);
  CHECK(text.find("over-confident separation points") != std::string::npos);
}

TEST_CASE("baseline: measured + margin for generated missions, the bounds for shipped ones; worse fails") {
  MissionResult gen = result("gen_1", 0.10, 0.02, 0.15, 4);
  MissionResult shipped = result("relay", 0.01, 0.01, 0.02, 0);
  shipped.generator_seed.reset();
  MissionResult noisy = result("concurrent_moves", 0.01, 0.058, 0.02, 0);  // strictly over its bound, by sampling
  noisy.generator_seed.reset();
  const auto entries = baseline_from({gen, shipped, noisy}, Bounds{}, 0.03);
  REQUIRE(entries.size() == 3);
  CHECK(entries[2].radius == doctest::Approx(0.088));
  CHECK(entries[2].radius_tolerant == 0.05);
  CHECK(entries[0].time == doctest::Approx(0.13));
  CHECK(entries[0].joint == doctest::Approx(0.18));
  CHECK(entries[0].joint_tolerant == doctest::Approx(0.105));
  CHECK(entries[0].overconfident_go_cells == 5);  // 4 + 10 % + 1
  CHECK(entries[1].time == 0.05);           // the bound: measured 0.01 + 0.03 is below it
  CHECK(entries[1].joint == 0.08);
  CHECK(entries[1].time_tolerant == 0.05);
  CHECK(entries[1].overconfident_go_cells == 0);

  const std::string path = p3at::test::scratch_path("baseline.json");
  std::ofstream(path) << baseline_json(entries, "test").dump(2);
  const auto loaded = load_baseline(path);
  REQUIRE(loaded.size() == 3);
  CHECK(loaded[0].joint == doctest::Approx(0.18));
  CHECK(check_baseline({gen, shipped}, loaded).empty());

  MissionResult worse = gen;
  worse.score.joint.strict = 0.19;
  MissionResult over = shipped;
  over.score.time.strict = 0.06;
  over.score.overconfident_go_cells = 1;
  MissionResult unknown = result("gen_99", 0, 0, 0, 0);
  const auto v = check_baseline({worse, over, unknown}, loaded);
  REQUIRE(v.size() == 4);
  CHECK(v[0] == "gen_1: joint strict 0.190 > 0.180");
  CHECK(v[1] == "relay: time strict 0.060 > 0.050");
  CHECK(v[2] == "relay: 1 over-confident GO cells > 0");
  CHECK(v[3].find("gen_99: not in the baseline") == 0);
  // An over-confident separation point fails on a mission the verifier vouches for, not on one it refuses.
  MissionResult unsafe = gen;
  unsafe.separation = SeparationScore{"1:2:0.1", ErrorSummary{}, 2};
  const auto s = check_baseline({unsafe}, loaded);
  REQUIRE(s.size() == 1);
  CHECK(s[0] == "gen_1: 2 over-confident separation points > 0");
  unsafe.evaluable = false;
  CHECK(check_baseline({unsafe}, loaded).empty());
  std::ofstream(path) << "{\"missions\": [{\"name\": 3}]}";
  CHECK_THROWS_AS(load_baseline(path), std::runtime_error);
  std::filesystem::remove(path);
}

TEST_CASE("JSON: a mission's result reads back as written (missions.jsonl, --from-results)") {
  MissionResult r = result("gen_9", 0.12, 0.04, 0.2, 3);
  r.score.time.strict_at_tmax_s = 180.5;
  r.score.joint.strict_at_rmax_m = 1.25;
  r.score.overconfident.push_back({180, 1.2, 0.9, 0.6, 0.55, 0.65});
  r.approximations = {"a", "b"};
  r.tmax_range = "170:190:0.5";
  r.reproduce = "vipars crosscheck --seeds 9:9";
  const MissionResult back = mission_result_from_json(nlohmann::json::parse(mission_result_json(r).dump()));
  CHECK(back.name == "gen_9");
  CHECK(back.generator_seed == r.generator_seed);
  CHECK(back.score.time.strict == 0.12);
  CHECK(back.score.time.strict_at_tmax_s == 180.5);
  CHECK(std::isnan(back.score.time.strict_at_rmax_m));
  CHECK(back.score.joint.strict_at_rmax_m == 1.25);
  CHECK(back.score.overconfident_go_cells == 3);
  REQUIRE(back.score.overconfident.size() == 1);
  CHECK(back.score.overconfident[0].ci_high == 0.65);
  CHECK(back.approximations == r.approximations);
  CHECK(back.tmax_range == r.tmax_range);
  CHECK(back.reproduce == r.reproduce);
  CHECK(mission_result_json(back).dump() == mission_result_json(r).dump());
  CHECK_THROWS(mission_result_from_json(nlohmann::json::parse("{\"name\": \"x\"}")));
}

TEST_CASE("each robot's final distance: kept through JSON (older files have none), its spreads' ratios in the summary") {
  // Five comparable robots whose verify spread is 0.5, 0.9, 1.0, 1.1 and 2.0
  // times the runs', and two that are not comparable (blocked in verify, or
  // failed runs): those never enter the ratios.
  std::vector<MissionResult> rs{result("a", 0.01, 0.01, 0.01, 0), result("b", 0.01, 0.01, 0.01, 0)};
  const double ratios[] = {0.5, 0.9, 1.0, 1.1, 2.0};
  for (int k = 0; k < 5; ++k) {
    rs[k < 3 ? 0 : 1].robot_distances.push_back(
        {"robot" + std::to_string(k), 1.0 + 0.001 * k, 0.01 * ratios[k], 1.0, 0.01, true});
  }
  rs[1].robot_distances.push_back({"blocked", 9.0, 5.0, 1.0, 0.01, false});
  const CampaignSummary s = summarize(rs, Bounds{});
  CHECK(s.robot_distances.robots == 5);
  CHECK(s.robot_distances.sd_ratio_p10 == doctest::Approx(0.5));
  CHECK(s.robot_distances.sd_ratio_p50 == doctest::Approx(1.0));
  CHECK(s.robot_distances.sd_ratio_p90 == doctest::Approx(2.0));
  CHECK(s.robot_distances.narrower == 1);
  CHECK(s.robot_distances.wider == 1);
  CHECK(s.robot_distances.mean_error_p50_m == doctest::Approx(0.002));
  CHECK(s.robot_distances.mean_error_worst_m == doctest::Approx(0.004));
  const std::string text = summary_text(s, Bounds{});
  CHECK(text.find("final distance per robot (5 comparable robots): verify's sd / the runs' p10 0.50, median 1.00, "
                  "p90 2.00; under 2/3 1, over 3/2 1; |mean difference| median 2.0 mm, p90 4.0 mm, worst 4.0 mm\n") !=
        std::string::npos);
  const auto sj = summary_json(s, Bounds{});
  CHECK(sj["robot_distances"]["robots"] == 5);
  CHECK(sj["robot_distances"]["narrower_than_two_thirds"] == 1);
  CHECK(sj["robot_distances"]["sd_ratio"]["p50"] == doctest::Approx(1.0));

  const MissionResult back = mission_result_from_json(nlohmann::json::parse(mission_result_json(rs[1]).dump()));
  REQUIRE(back.robot_distances.size() == 3);
  CHECK(back.robot_distances[2].name == "blocked");
  CHECK_FALSE(back.robot_distances[2].comparable);
  CHECK(back.robot_distances[0].verify_sd_m == doctest::Approx(0.011));
  // A file written before the key reads back without robots, and the summary says nothing of them.
  nlohmann::json old = nlohmann::json::parse(mission_result_json(rs[0]).dump());
  old.erase("robot_distances");
  CHECK(mission_result_from_json(old).robot_distances.empty());
  CHECK(summary_text(summarize({mission_result_from_json(old)}, Bounds{}), Bounds{}).find("final distance") ==
        std::string::npos);
  // Each step's seconds, scoring's too; a file written before scoring had its figure reads back 0.
  MissionResult timed = rs[0];
  timed.verify_s = 1.5;
  timed.score_s = 2.25;
  const MissionResult timed_back = mission_result_from_json(nlohmann::json::parse(mission_result_json(timed).dump()));
  CHECK(timed_back.verify_s == 1.5);
  CHECK(timed_back.score_s == 2.25);
  nlohmann::json untimed = mission_result_json(timed);
  untimed["seconds"].erase("score");
  CHECK(mission_result_from_json(untimed).score_s == 0.0);
}
