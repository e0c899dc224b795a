// `vipars validate` as a user runs it (the built binary, examples/relay):
// output byte-identical for any --jobs, exactly the JSON keys shared with
// `vipars verify`, probabilities that match the per-run CSV, exit statuses
// for bad input and for campaigns where no run completes, and a run
// replayed alone by `vipars simulate` from its CSV seed.

#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using Json = nlohmann::ordered_json;
using p3at::test::read_file;
using Outcome = p3at::test::CommandOutcome;

const std::string kMission = std::string(P3AT_SOURCE_DIR) + "/examples/relay/mission.yaml";
const std::string kWorld = std::string(P3AT_SOURCE_DIR) + "/examples/relay/world.yaml";

using p3at::test::scratch_path;

// Runs vipars with `args` (already shell-quoted where needed); stdout and
// stderr captured separately (stderr carries timing, stdout must not).
Outcome vipars(const std::string& args) { return p3at::test::run_command("'" + std::string(P3AT_VIPARS_BIN) + "' " + args); }

std::string validate_args(const std::string& extra) {
  return "validate '" + kMission + "' --world '" + kWorld + "' " + extra;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep)) parts.push_back(part);
  return parts;
}

std::vector<std::string> keys(const Json& object) {
  std::vector<std::string> k;
  for (const auto& item : object.items()) k.push_back(item.key());
  return k;
}

}  // namespace

TEST_CASE("output and CSV are byte-identical on 1 and 3 threads") {
  const std::string grid = "--trials 12 --seed 5 --tmax-range 20:40:5 --rmax-range 0.1:0.5:0.1";
  const std::string csv1 = scratch_path("j1.csv"), csv3 = scratch_path("j3.csv");
  const Outcome j1 = vipars(validate_args(grid + " --jobs 1 --json --csv '" + csv1 + "'"));
  const Outcome j3 = vipars(validate_args(grid + " --jobs 3 --json --csv '" + csv3 + "'"));
  CHECK(j1.status == 0);
  CHECK(j3.status == 0);
  CHECK_FALSE(j1.out.empty());
  CHECK(j1.out == j3.out);
  const std::string rows1 = read_file(csv1);
  CHECK(split(rows1, '\n').size() == 13);  // header + 12 runs
  CHECK(rows1 == read_file(csv3));
  // Not a terminal: no progress bar, one summary line.
  CHECK(j1.err.find("vipars validate: runs=12 failed=0 jobs=1 ") == 0);
  CHECK(j3.err.find("jobs=3 ") != std::string::npos);
  const Outcome t1 = vipars(validate_args(grid + " --jobs 1"));
  const Outcome t3 = vipars(validate_args(grid + " --jobs 3"));
  CHECK(t1.status == 0);
  CHECK(t1.out == t3.out);
  CHECK(t1.out.find("validation of relay: 12 runs from seed 5, 0 failed") != std::string::npos);
  std::remove(csv1.c_str());
  std::remove(csv3.c_str());
}

TEST_CASE("JSON: exactly the keys shared with verify, shapes, and the CSV's counts") {
  const std::string csv = scratch_path("runs.csv");
  const Outcome o = vipars(validate_args("--trials 10 --seed 9 --jobs 2 --tmax 25 --rmax 0.3 --json "
                                         "--tmax-range 20:30:5 --rmax-range 0.1:0.4:0.1 --csv '" + csv + "'"));
  REQUIRE(o.status == 0);
  const Json j = Json::parse(o.out);
  CHECK(keys(j) == std::vector<std::string>{"mission", "tmax_s", "rmax_m", "threshold", "p_time", "p_time_ci_low",
                                            "p_time_ci_high", "p_radius", "p_radius_ci_low", "p_radius_ci_high",
                                            "p_joint", "p_joint_ci_low", "p_joint_ci_high", "runs", "failed_runs",
                                            "robots", "completion_mean_s", "completion_sd_s", "grid", "seed",
                                            "world", "mission_file"});
  CHECK(j["mission"] == "relay");
  CHECK(j["tmax_s"] == 25.0);    // --tmax overrides the mission's 60
  CHECK(j["rmax_m"] == 0.3);
  CHECK(j["threshold"] == 0.8);  // the mission's
  CHECK(j["runs"] == 10);
  CHECK(j["failed_runs"] == 0);
  CHECK(j["seed"] == 9);
  CHECK(j["world"] == kWorld);
  CHECK(j["mission_file"] == kMission);
  REQUIRE(j["robots"].size() == 2);
  CHECK(keys(j["robots"][0]) == std::vector<std::string>{"name", "p_radius", "p_radius_ci_low", "p_radius_ci_high",
                                                         "dist_mean_m", "dist_sd_m"});
  CHECK(j["robots"][1]["name"] == "robot2");
  const Json& g = j["grid"];
  CHECK(keys(g) == std::vector<std::string>{"tmax", "rmax", "p_time", "p_radius", "p_joint", "region",
                                            "p_time_ci_low", "p_time_ci_high", "p_radius_ci_low",
                                            "p_radius_ci_high", "p_joint_ci_low", "p_joint_ci_high"});
  CHECK(g["tmax"] == Json::array({20.0, 25.0, 30.0}));
  CHECK(g["rmax"] == Json::array({0.1, 0.2, 0.3, 0.4}));
  for (const char* key : {"p_time", "p_time_ci_low", "p_time_ci_high"}) CHECK(g[key].size() == 3);
  for (const char* key : {"p_radius", "p_radius_ci_low", "p_radius_ci_high"}) CHECK(g[key].size() == 4);
  for (const char* key : {"p_joint", "p_joint_ci_low", "p_joint_ci_high", "region"}) {
    REQUIRE(g[key].size() == 3);
    for (const auto& row : g[key]) CHECK(row.size() == 4);
  }
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = 0; b < 4; ++b) {
      const double p = g["p_joint"][a][b];
      const std::string region = g["region"][a][b];
      CHECK(region == (p < 0.05 ? "unsuccessful" : p >= 0.95 ? "successful" : "uncertain"));
      CHECK(g["p_joint_ci_low"][a][b].get<double>() <= p);
      CHECK(g["p_joint_ci_high"][a][b].get<double>() >= p);
    }
  }
  // The grid's cell at (25 s, 0.3 m) is the top-level point.
  CHECK(g["p_joint"][1][2] == j["p_joint"]);
  CHECK(g["p_time"][1] == j["p_time"]);
  CHECK(g["p_radius"][2] == j["p_radius"]);

  // Recount the point from the CSV: run,seed,outcome,time_s,dist_robot1_m,dist_robot2_m,closest,phase1,phase2.
  const auto lines = split(read_file(csv), '\n');
  REQUIRE(lines.size() == 11);
  CHECK(lines[0] == "run,seed,outcome,time_s,dist_robot1_m,dist_robot2_m,closest_approach_m,phase_robot1,phase_robot2");
  int time_ok = 0, radius_ok = 0, joint_ok = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = split(lines[i], ',');
    REQUIRE(f.size() == 9);
    CHECK(f[0] == std::to_string(i - 1));
    CHECK(f[2] == "success");
    CHECK(f[7] == "finished");
    const bool t = std::stod(f[3]) <= 25.0;
    const bool r = std::stod(f[4]) <= 0.3 && std::stod(f[5]) <= 0.3;
    time_ok += t ? 1 : 0;
    radius_ok += r ? 1 : 0;
    joint_ok += t && r ? 1 : 0;
  }
  CHECK(j["p_time"].get<double>() == doctest::Approx(time_ok / 10.0));
  CHECK(j["p_radius"].get<double>() == doctest::Approx(radius_ok / 10.0));
  CHECK(j["p_joint"].get<double>() == doctest::Approx(joint_ok / 10.0));
  std::remove(csv.c_str());
}

TEST_CASE("no grid without ranges; defaults from the mission's criteria") {
  const Outcome o = vipars(validate_args("--trials 3 --json"));
  REQUIRE(o.status == 0);
  const Json j = Json::parse(o.out);
  CHECK_FALSE(j.contains("grid"));
  CHECK(j["tmax_s"] == 60.0);
  CHECK(j["rmax_m"] == 0.5);
  CHECK(j["seed"] == 1);
}

TEST_CASE("a campaign where no run completes: reported, exit status 3") {
  const Outcome o = vipars(validate_args("--trials 4 --timeout 3 --json"));
  CHECK(o.status == 3);
  const Json j = Json::parse(o.out);
  CHECK(j["runs"] == 4);
  CHECK(j["failed_runs"] == 4);
  CHECK(j["p_time"] == 0.0);
  CHECK(j["completion_mean_s"].is_null());
  const Outcome text = vipars(validate_args("--trials 4 --timeout 3"));
  CHECK(text.status == 3);
  CHECK(text.out.find("4 failed") != std::string::npos);
  CHECK(text.out.find("4 x timeout") != std::string::npos);
}

TEST_CASE("bad input: exit status 2 and a message that says what is wrong") {
  const Outcome missing = vipars("validate /nonexistent/m.yaml --world '" + kWorld + "' --trials 2");
  CHECK(missing.status == 2);
  CHECK(missing.err.find("/nonexistent/m.yaml") != std::string::npos);

  const std::string bad_mission = scratch_path("bad.yaml");
  {
    std::ofstream f(bad_mission);
    f << "mission:\n  name: x\n  colour: red\n";
  }
  const Outcome bad = vipars("validate '" + bad_mission + "' --world '" + kWorld + "' --trials 2");
  CHECK(bad.status == 2);
  CHECK(bad.err.find(bad_mission + ":") != std::string::npos);  // file:line:column
  std::remove(bad_mission.c_str());

  const Outcome range = vipars(validate_args("--trials 2 --rmax-range 1:3:0"));
  CHECK(range.status == 2);
  CHECK(range.err == "vipars validate: --rmax-range: expected A:B:STEP with STEP > 0, got '1:3:0'\n");

  const Outcome trials = vipars(validate_args("--trials 0"));
  CHECK(trials.status == 2);
  CHECK(trials.err.find("--trials") != std::string::npos);

  const Outcome tmax = vipars(validate_args("--trials 2 --tmax -5"));
  CHECK(tmax.status == 2);
  CHECK(tmax.err.find("--tmax") != std::string::npos);

  const Outcome regions = vipars(validate_args("--trials 2 --region-low 0.9 --region-high 0.5"));
  CHECK(regions.status == 2);
}

TEST_CASE("a run replays alone with vipars simulate from its CSV seed") {
  const std::string validate_csv = scratch_path("v.csv"), simulate_csv = scratch_path("s.csv");
  REQUIRE(vipars(validate_args("--trials 4 --seed 11 --csv '" + validate_csv + "'")).status == 0);
  const auto row = split(split(read_file(validate_csv), '\n').at(4), ',');  // run 3
  REQUIRE(row.size() == 9);
  const Outcome sim = vipars("simulate '" + kMission + "' --world '" + kWorld + "' --runs 1 --seed " + row[1] +
                             " --csv '" + simulate_csv + "'");
  REQUIRE(sim.status == 0);
  const auto replay = split(split(read_file(simulate_csv), '\n').at(1), ',');
  REQUIRE(replay.size() == 7);
  CHECK(replay[0] == "0");
  for (std::size_t i = 1; i < 7; ++i) CHECK(replay[i] == row[i]);  // seed, outcome, time, distances, approach
  std::remove(validate_csv.c_str());
  std::remove(simulate_csv.c_str());
}
