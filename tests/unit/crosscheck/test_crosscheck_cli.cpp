// `vipars generate` and `vipars crosscheck` as a user runs them (the built
// binary, a small generated one-robot mission): the campaign's results do
// not depend on --jobs, every file of the mission's folder is there, the
// commands it prints remake verify.json and validate.json exactly,
// --from-results gives the same summary, a baseline it is worse than fails
// it, and bad flags are exit 2.

#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_run.hpp"
#include "p3at/team_sim/part_file.hpp"

namespace {

namespace fs = std::filesystem;
using p3at::test::read_file;
using Outcome = p3at::test::CommandOutcome;

// `command` run in `dir` (its stdout and stderr captured).
Outcome run(const std::string& command, const fs::path& dir) { return p3at::test::run_command(command, dir.string()); }

const std::string kVipars = "'" + std::string(P3AT_VIPARS_BIN) + "'";
// Seed 5 with one robot: a 30 s mission in an open room.
const std::string kCampaign = " crosscheck --seeds 5:5 --robots 1:1 --runs 40 --calibration-runs 4 --no-report";

nlohmann::json without_timing(nlohmann::json j) {
  for (auto& m : j["missions"]) {
    m.erase("seconds");
    m.erase("folder");
    m.erase("reproduce");
  }
  j.erase("command");
  return j;
}

}  // namespace

TEST_CASE("vipars crosscheck: the same results for any --jobs, a folder that remakes itself") {
  const fs::path dir = p3at::test::scratch_dir("crosscheck-cli");
  const Outcome one = run(kVipars + kCampaign + " --jobs 1 --out a", dir);
  REQUIRE(one.status == 0);
  const Outcome two = run(kVipars + kCampaign + " --jobs 2 --out b", dir);
  REQUIRE(two.status == 0);
  CHECK(one.out.find("gen_5 ") == 0);
  CHECK(one.out.find("missions 1: scored 1") != std::string::npos);
  const auto ja = nlohmann::json::parse(read_file(dir / "a" / "crosscheck.json"));
  const auto jb = nlohmann::json::parse(read_file(dir / "b" / "crosscheck.json"));
  CHECK(without_timing(ja) == without_timing(jb));
  CHECK(read_file(dir / "a/missions/gen_5/validate.json") == read_file(dir / "b/missions/gen_5/validate.json"));
  CHECK(read_file(dir / "a/missions/gen_5/verify.json") == read_file(dir / "b/missions/gen_5/verify.json"));
  CHECK(ja["missions"][0]["runs"] == 40);
  CHECK(ja["summary"]["scored"] == 1);

  // The folder: the mission as `vipars generate` writes it, and every document.
  const fs::path m = dir / "a/missions/gen_5";
  const Outcome gen = run(kVipars + " generate --seed 5 --robots 1:1 --out g", dir);
  REQUIRE(gen.status == 0);
  CHECK(read_file(dir / "g/mission.yaml") == read_file(m / "mission.yaml"));
  CHECK(read_file(dir / "g/world.yaml") == read_file(m / "world.yaml"));
  for (const char* f : {"models.yaml", "calibration.txt", "verify.json", "validate.json", "score.json", "commands.txt"}) {
    CHECK(fs::is_regular_file(m / f));
  }

  // The documents' own commands remake them exactly.
  const auto v = nlohmann::json::parse(read_file(m / "verify.json"));
  const auto w = nlohmann::json::parse(read_file(m / "validate.json"));
  std::string vc = v["command"].get<std::string>(), wc = w["command"].get<std::string>();
  vc.replace(0, std::string("vipars").size(), kVipars);
  wc.replace(0, std::string("vipars").size(), kVipars);
  const Outcome vr = run(vc, m);
  const Outcome wr = run(wc, m);
  auto v2 = nlohmann::json::parse(vr.out), w2 = nlohmann::json::parse(wr.out);
  v2["command"] = v["command"];
  w2["command"] = w["command"];
  CHECK(v2 == v);
  CHECK(w2 == w);

  // The summary again from missions.jsonl.
  const Outcome again = run(kVipars + " crosscheck --from-results --no-report --out a", dir);
  CHECK(again.status == 0);
  CHECK(again.out.find("missions 1: scored 1") != std::string::npos);

  // A baseline it is worse than: exit 1, naming the mission.
  std::ofstream(dir / "tight.json") << R"({"missions": [{"name": "gen_5", "time": -1, "radius": 1, "joint": 1,
    "time_tolerant": 1, "radius_tolerant": 1, "joint_tolerant": 1, "overconfident_go_cells": 1000}]})";
  const Outcome worse = run(kVipars + " crosscheck --from-results --no-report --out a --baseline tight.json", dir);
  CHECK(worse.status == 1);
  CHECK(worse.err.find("gen_5: time strict") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("vipars crosscheck --runs-only makes the runs a later --reuse-runs campaign scores, unchanged") {
  const fs::path dir = p3at::test::scratch_dir("crosscheck-runs-only");
  const Outcome only = run(kVipars + kCampaign + " --runs-only --out b", dir);
  REQUIRE(only.status == 0);
  CHECK(fs::is_regular_file(dir / "b/missions/gen_5/runs.part"));
  CHECK(!fs::exists(dir / "b/missions.jsonl"));                   // nothing scored
  CHECK(!fs::exists(dir / "b/missions/gen_5/verify.json"));      // nothing verified
  CHECK(only.out.find("kept in") != std::string::npos);
  // Again: the runs are there already and are kept as they are.
  const Outcome again = run(kVipars + kCampaign + " --runs-only --out b", dir);
  REQUIRE(again.status == 0);
  CHECK(again.out.find("already in") != std::string::npos);
  // Scored with --reuse-runs: the same results as a campaign that made its own runs.
  const Outcome scored = run(kVipars + kCampaign + " --reuse-runs --out b", dir);
  REQUIRE(scored.status == 0);
  CHECK(scored.err.find("validation runs reused from its runs.part") != std::string::npos);
  const Outcome fresh = run(kVipars + kCampaign + " --out c", dir);
  REQUIRE(fresh.status == 0);
  const auto strip = [](nlohmann::json j) {
    j = without_timing(j);
    j.erase("command");
    for (auto& m : j["missions"]) {
      m.erase("folder");
      m.erase("reproduce");
    }
    return j;
  };
  CHECK(strip(nlohmann::json::parse(read_file(dir / "b/crosscheck.json"))) ==
        strip(nlohmann::json::parse(read_file(dir / "c/crosscheck.json"))));
  CHECK(read_file(dir / "b/missions/gen_5/validate.json") == read_file(dir / "c/missions/gen_5/validate.json"));
  fs::remove_all(dir);
}

TEST_CASE("vipars crosscheck --reuse-runs: the folder's runs give the same results; other or damaged runs are not used") {
  const fs::path dir = p3at::test::scratch_dir("crosscheck-reuse");
  const std::string campaign = kVipars + kCampaign + " --reuse-runs --out a";
  const Outcome first = run(campaign, dir);
  REQUIRE(first.status == 0);
  const fs::path part = dir / "a/missions/gen_5/runs.part";
  REQUIRE(fs::is_regular_file(part));
  CHECK(first.err.find("reused") == std::string::npos);  // nothing to reuse yet
  const auto fresh = nlohmann::json::parse(read_file(dir / "a/crosscheck.json"));
  const std::string validate = read_file(dir / "a/missions/gen_5/validate.json");

  const Outcome second = run(campaign, dir);
  REQUIRE(second.status == 0);
  CHECK(second.err.find("gen_5 done in") != std::string::npos);
  CHECK(second.err.find("validation runs reused from its runs.part") != std::string::npos);
  CHECK(without_timing(nlohmann::json::parse(read_file(dir / "a/crosscheck.json"))) == without_timing(fresh));
  CHECK(read_file(dir / "a/missions/gen_5/validate.json") == validate);

  // Another campaign seed makes other runs: the cached ones are not used.
  const Outcome other = run(kVipars + kCampaign + " --reuse-runs --seed 2 --out a", dir);
  REQUIRE(other.status == 0);
  CHECK(other.err.find("reused") == std::string::npos);

  // A damaged file (one byte changed) is refused by its checksum and the runs are made again.
  (void)run(kVipars + kCampaign + " --reuse-runs --out a", dir);  // the seed-1 runs back in place
  std::string bytes = read_file(part);
  const std::size_t at = bytes.find("success");
  REQUIRE(at != std::string::npos);
  bytes[at] = 'S';
  std::ofstream(part, std::ios::binary | std::ios::trunc) << bytes;
  const Outcome damaged = run(campaign, dir);
  REQUIRE(damaged.status == 0);
  CHECK(damaged.err.find("not reusing") != std::string::npos);
  CHECK(damaged.err.find("reused from") == std::string::npos);
  CHECK(without_timing(nlohmann::json::parse(read_file(dir / "a/crosscheck.json"))) == without_timing(fresh));

  // Runs of an older vipars, whose distances were where the last trigger
  // fired rather than where the robot came to rest: their file is intact
  // (valid checksum), but its format version says so; refused, runs made again.
  bytes = read_file(part);
  const std::string v2 = "vipars-validation-part\t2\n";
  REQUIRE(bytes.rfind(v2, 0) == 0);
  std::string body = "vipars-validation-part\t1\n" + bytes.substr(v2.size(), bytes.rfind("end\t") - v2.size());
  const std::string end_line = bytes.substr(bytes.rfind("end\t"));
  const std::string runs_field = end_line.substr(4, end_line.find('\t', 4) - 4);
  std::ofstream(part, std::ios::binary | std::ios::trunc)
      << body << "end\t" << runs_field << "\tblake2b-256\t" << p3at::team_sim::part_checksum(body) << "\n";
  const Outcome old = run(campaign, dir);
  REQUIRE(old.status == 0);
  CHECK(old.err.find("not reusing") != std::string::npos);
  CHECK(old.err.find("part format version 1") != std::string::npos);
  CHECK(old.err.find("reused from") == std::string::npos);
  CHECK(without_timing(nlohmann::json::parse(read_file(dir / "a/crosscheck.json"))) == without_timing(fresh));
  CHECK(read_file(part).rfind(v2, 0) == 0);  // the runs made again, in the current format
  fs::remove_all(dir);
}

TEST_CASE("vipars crosscheck and generate: bad input is exit 2 with a message") {
  const fs::path dir = p3at::test::scratch_dir("crosscheck-bad-input");
  Outcome o = run(kVipars + " crosscheck --seeds 5:5 --robots 0:3", dir);
  CHECK(o.status == 2);
  CHECK(o.err.find("--robots") != std::string::npos);
  o = run(kVipars + " crosscheck --seeds 9:3", dir);
  CHECK(o.status == 2);
  o = run(kVipars + " crosscheck --out /tmp", dir);
  CHECK(o.status == 2);
  CHECK(o.err.find("no missions") != std::string::npos);
  o = run(kVipars + " crosscheck --missions /nonexistent-folder", dir);
  CHECK(o.status == 2);
  o = run(kVipars + " generate --seeds 3", dir);
  CHECK(o.status == 2);
  o = run(kVipars + " generate --seed 1 --robots 2:7", dir);
  CHECK(o.status == 2);
}
