// `vipars report` as a user runs it (the built binary, the Bounding Overwatch
// example, a small campaign): in both modes the data files hold exactly the
// numbers of the JSON documents the report was made from, the exit status
// follows errors.json, the commands the documents carry remake them, and bad
// input exits 2 with a message.

#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;
using p3at::test::read_file;
using Outcome = p3at::test::CommandOutcome;

const std::string kExample = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/";
const std::string kMission = kExample + "mission.yaml";
const std::string kModels = kExample + "models.yaml";
const std::string kWorld = kExample + "world.yaml";
// A small grid across the example's rise (P(t) from ~185 s, P(r) from ~1.8 m) and few runs: seconds.
const std::string kRanges = "--tmax-range 180:215:5 --rmax-range 1.5:2.5:0.25";

using p3at::test::scratch_dir;

// Runs a shell command line in `dir` (vipars's path substituted for a leading "vipars").
Outcome sh(const std::string& dir, const std::string& command) {
  std::string line = command;
  if (line.rfind("vipars ", 0) == 0) line = "'" + std::string(P3AT_VIPARS_BIN) + "'" + line.substr(6);
  return p3at::test::run_command(line, dir);
}

std::vector<std::vector<double>> rows(const std::string& path) {
  std::vector<std::vector<double>> out;
  std::istringstream in(read_file(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> row;
    std::string f;
    while (fields >> f) row.push_back(std::strtod(f.c_str(), nullptr));
    out.push_back(row);
  }
  return out;
}

double d(const Json& j) { return j.get<double>(); }

// The data files of `out_dir` hold the documents' numbers exactly.
void check_data_matches(const std::string& out_dir, const Json& v, const Json& w) {
  const Json& vg = v["grid"];
  const Json& wg = w["grid"];
  const auto time = rows(out_dir + "/fig09_time.dat");
  REQUIRE(time.size() == vg["tmax"].size());
  for (std::size_t i = 0; i < time.size(); ++i) {
    CHECK(time[i][0] == d(vg["tmax"][i]));
    CHECK(time[i][1] == d(vg["p_time"][i]));
    CHECK(time[i][2] == d(wg["p_time"][i]));
    CHECK(time[i][3] == d(wg["p_time_ci_low"][i]));
    CHECK(time[i][4] == d(wg["p_time_ci_high"][i]));
  }
  const auto radius = rows(out_dir + "/fig10_radius.dat");
  REQUIRE(radius.size() == vg["rmax"].size());
  for (std::size_t j = 0; j < radius.size(); ++j) {
    CHECK(radius[j][0] == d(vg["rmax"][j]));
    CHECK(radius[j][1] == d(vg["p_radius"][j]));
    CHECK(radius[j][2] == d(wg["p_radius"][j]));
  }
  const auto joint = rows(out_dir + "/fig11_joint.dat");
  REQUIRE(joint.size() == vg["tmax"].size() * vg["rmax"].size());
  double max_error = 0.0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < vg["tmax"].size(); ++i) {
    for (std::size_t j = 0; j < vg["rmax"].size(); ++j, ++k) {
      CHECK(joint[k][2] == d(vg["p_joint"][i][j]));
      CHECK(joint[k][3] == d(wg["p_joint"][i][j]));
      CHECK(joint[k][4] == d(wg["p_joint_ci_low"][i][j]));
      CHECK(joint[k][5] == d(wg["p_joint_ci_high"][i][j]));
      max_error = std::max(max_error, std::abs(d(vg["p_joint"][i][j]) - d(wg["p_joint"][i][j])));
    }
  }
  const Json errors = Json::parse(read_file(out_dir + "/errors.json"));
  CHECK(d(errors["joint"]["max_abs_error"]) == max_error);
}

}  // namespace

TEST_CASE("one run: verify and validate here, then the report from the documents it wrote") {
  const std::string dir = scratch_dir("run");
  const Outcome o = sh(dir, "vipars report '" + kMission + "' --models '" + kModels + "' --world '" + kWorld +
                                "' --trials 24 --jobs 2 " + kRanges + " --out rep --no-plots");
  INFO(o.err);
  REQUIRE((o.status == 0 || o.status == 1));
  const Json v = Json::parse(read_file(dir + "/rep/verify.json"));
  const Json w = Json::parse(read_file(dir + "/rep/validate.json"));
  CHECK(w["runs"] == 24);
  CHECK(v.contains("decision"));
  check_data_matches(dir + "/rep", v, w);
  const Json errors = Json::parse(read_file(dir + "/rep/errors.json"));
  CHECK(o.status == (errors["pass"].get<bool>() ? 0 : 1));
  CHECK(o.out.find("report in rep/index.html") != std::string::npos);
  CHECK(o.err.find("validating: 24 runs on 2 thread(s)") != std::string::npos);  // progress
  const std::string html = read_file(dir + "/rep/index.html");
  CHECK(html.find("world (--world)") != std::string::npos);
  CHECK(html.find("Made in one run") != std::string::npos);

  SUBCASE("the documents' commands remake the same documents") {
    for (const Json* doc : {&v, &w}) {
      const std::string command = (*doc)["command"].get<std::string>();
      const Outcome again = sh(dir, command + " > again.json");
      INFO(command, ": ", again.err);
      CHECK(command.rfind(doc == &v ? "vipars verify " : "vipars validate ", 0) == 0);
      CHECK((again.status == 0 || again.status == 1));  // verify: 1 is NO-GO
      Json expected = *doc;
      expected.erase("command");
      CHECK(Json::parse(read_file(dir + "/again.json")) == expected);
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("from documents: vipars verify and vipars validate's own JSON") {
  const std::string dir = scratch_dir("files");
  const Outcome vo =
      sh(dir, "vipars verify '" + kMission + "' --models '" + kModels + "' " + kRanges + " --json > v.json");
  REQUIRE((vo.status == 0 || vo.status == 1));
  const Outcome wo = sh(
      dir, "vipars validate '" + kMission + "' --world '" + kWorld + "' --trials 16 " + kRanges + " --json > w.json");
  REQUIRE(wo.status == 0);
  const Outcome o = sh(dir, "vipars report --verify v.json --validate w.json --models '" + kModels +
                                "' --out rep --no-plots --rmax-slices 2,2.25 --title 'BO test'");
  INFO(o.err);
  REQUIRE((o.status == 0 || o.status == 1));
  check_data_matches(dir + "/rep", Json::parse(read_file(dir + "/v.json")), Json::parse(read_file(dir + "/w.json")));
  // Two slices asked, two data sets; the page rebuilt the commands from the documents.
  CHECK(read_file(dir + "/rep/fig12_slices_tmax.dat").find("# rmax_m 2.25\n") != std::string::npos);
  const std::string html = read_file(dir + "/rep/index.html");
  CHECK(html.find("vipars validate " + kMission + " --world " + kWorld + " --trials 16 --seed 1") != std::string::npos);
  CHECK(html.find("--tmax-range 180:215:5 --rmax-range 1.5:2.5:0.25") != std::string::npos);
  CHECK(html.find("mission (named in the validation)") != std::string::npos);  // hashed: the file is here
  CHECK(html.find("<h1>BO test: verification vs. validation</h1>") != std::string::npos);

  SUBCASE("bad input exits 2 and says why") {
    const Outcome swapped = sh(dir, "vipars report --verify w.json --validate v.json --out bad --no-plots");
    CHECK(swapped.status == 2);
    CHECK(swapped.err.find("w.json: expected the output of `vipars verify --json`") != std::string::npos);
    CHECK_FALSE(fs::exists(dir + "/bad"));

    const Outcome no_grid_doc =
        sh(dir, "vipars verify '" + kMission + "' --models '" + kModels + "' --json > point.json");
    CHECK((no_grid_doc.status == 0 || no_grid_doc.status == 1));
    const Outcome no_grid = sh(dir, "vipars report --verify point.json --validate w.json --out bad --no-plots");
    CHECK(no_grid.status == 2);
    CHECK(no_grid.err.find("point.json: missing key 'grid'") != std::string::npos);

    const Outcome other_grid = sh(dir, "vipars verify '" + kMission + "' --models '" + kModels +
                                           "' --tmax-range 180:215:7 --rmax-range 1.5:2.5:0.25 --json > other.json");
    CHECK((other_grid.status == 0 || other_grid.status == 1));
    const Outcome mismatch = sh(dir, "vipars report --verify other.json --validate w.json --out bad --no-plots");
    CHECK(mismatch.status == 2);
    CHECK(mismatch.err.find("the grids differ: tmax has 6 values 180..215 in other.json but 8 values 180..215 in "
                            "w.json") != std::string::npos);

    const Outcome both = sh(dir, "vipars report '" + kMission + "' --verify v.json --validate w.json --out bad");
    CHECK(both.status == 2);
    CHECK(both.err.find("not both") != std::string::npos);
    const Outcome run_flags = sh(dir, "vipars report --verify v.json --validate w.json --trials 5 --out bad");
    CHECK(run_flags.status == 2);
    CHECK(run_flags.err.find("are for MISSION") != std::string::npos);
    const Outcome neither = sh(dir, "vipars report --out bad");
    CHECK(neither.status == 2);
    const Outcome no_trials = sh(dir, "vipars report '" + kMission + "' --models '" + kModels + "' --world '" + kWorld +
                                          "' " + kRanges + " --out bad");
    CHECK(no_trials.status == 2);
    CHECK(no_trials.err.find("--trials: required") != std::string::npos);
    std::ofstream(dir + "/broken.json") << "{\n  \"grid\": [1,,2]\n}\n";
    const Outcome bad_json = sh(dir, "vipars report --verify broken.json --validate w.json --out bad");
    CHECK(bad_json.status == 2);
    CHECK(bad_json.err.find("broken.json:2:14: expected JSON") != std::string::npos);
    CHECK_FALSE(fs::exists(dir + "/bad"));
  }
  fs::remove_all(dir);
}
