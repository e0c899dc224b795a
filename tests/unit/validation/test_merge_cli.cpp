// `vipars validate --shard I/N --part FILE` and `vipars merge` as a user runs
// them (the built binary, examples/relay; docs/cluster.md): the merged JSON,
// text and CSV are byte for byte the unsharded campaign's, whatever order
// the parts are given in, including a campaign whose runs time out; merge
// refuses a damaged part, another campaign's part, a shard twice and a
// missing shard with exit 2 and a message naming the file or the shard; the
// flags' misuse is exit 2 naming the flag. The same through a real Slurm:
// scripts/test-slurm.sh.

#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using p3at::test::read_file;
using p3at::test::write_file;
using Outcome = p3at::test::CommandOutcome;

const std::string kMission = std::string(P3AT_SOURCE_DIR) + "/examples/relay/mission.yaml";
const std::string kWorld = std::string(P3AT_SOURCE_DIR) + "/examples/relay/world.yaml";

using p3at::test::scratch_path;

// The built vipars with `args` (already shell-quoted where needed).
Outcome vipars(const std::string& args) { return p3at::test::run_command("'" + std::string(P3AT_VIPARS_BIN) + "' " + args); }

std::string campaign(const std::string& extra) {
  return "validate '" + kMission + "' --world '" + kWorld + "' --trials 9 --seed 4 " + extra;
}

// The campaign's parts, shard i in parts[i].
std::vector<std::string> make_parts(const std::string& extra, int shards) {
  std::vector<std::string> parts;
  for (int i = 0; i < shards; ++i) {
    parts.push_back(scratch_path("shard-" + std::to_string(i) + ".part"));
    const Outcome o = vipars(campaign(extra) + " --jobs 1 --shard " + std::to_string(i) + "/" + std::to_string(shards) +
                             " --part '" + parts.back() + "'");
    REQUIRE_MESSAGE(o.status == 0, o.err);
    CHECK(o.out.empty());  // a shard prints no report
    CHECK(o.err.find("shard=" + std::to_string(i) + "/" + std::to_string(shards)) != std::string::npos);
  }
  return parts;
}

std::string quoted(const std::vector<std::string>& files, const std::vector<int>& order) {
  std::string s;
  for (int i : order) s += " '" + files[static_cast<std::size_t>(i)] + "'";
  return s;
}

void remove_all(const std::vector<std::string>& files) {
  for (const auto& f : files) std::remove(f.c_str());
}

// Unsharded and merged: JSON, CSV and text byte for byte.
void check_merge_is_unsharded(const std::string& extra, int shards, const std::vector<int>& order) {
  const std::string whole_csv = scratch_path("whole.csv"), merged_csv = scratch_path("merged.csv");
  const Outcome whole_json = vipars(campaign(extra) + " --json --csv '" + whole_csv + "'");
  const Outcome whole_text = vipars(campaign(extra));
  const auto parts = make_parts(extra, shards);
  const Outcome merged_json = vipars("merge" + quoted(parts, order) + " --json --csv '" + merged_csv + "'");
  const Outcome merged_text = vipars("merge" + quoted(parts, order));
  CHECK(merged_json.status == whole_json.status);
  CHECK(merged_text.status == whole_text.status);
  CHECK(!whole_json.out.empty());
  CHECK(merged_json.out == whole_json.out);
  CHECK(merged_text.out == whole_text.out);
  CHECK(read_file(merged_csv) == read_file(whole_csv));
  CHECK(merged_json.err.find("vipars merge: merged 9 of 9 runs expected from " + std::to_string(shards) + " parts") !=
        std::string::npos);
  remove_all(parts);
  remove_all({whole_csv, merged_csv});
}

}  // namespace

TEST_CASE("merged shards print the unsharded campaign's JSON, text and CSV byte for byte, in any order") {
  check_merge_is_unsharded("--tmax-range 14:18:0.5 --rmax-range 0.1:0.4:0.05", 3, {2, 0, 1});
  check_merge_is_unsharded("", 4, {3, 1, 2, 0});
  check_merge_is_unsharded("", 1, {0});
  // Every run times out: validate and merge both exit 3 with the same report.
  check_merge_is_unsharded("--timeout 10", 2, {1, 0});
}

TEST_CASE("merge refuses a damaged part, another campaign, a shard twice and a missing shard") {
  const auto parts = make_parts("", 3);
  SUBCASE("a missing shard names the one to rerun") {
    const Outcome o = vipars("merge" + quoted(parts, {2, 0}));
    CHECK(o.status == 2);
    CHECK(o.out.empty());
    CHECK(o.err.find("missing 1 of 3 shards: shard 1/3 (runs 3..5); rerun it with --shard 1/3") != std::string::npos);
    CHECK(o.err.find("merged 6 of 9 runs expected from 2 parts") != std::string::npos);
  }
  SUBCASE("a shard twice") {
    const Outcome o = vipars("merge" + quoted(parts, {0, 1, 2, 1}));
    CHECK(o.status == 2);
    CHECK(o.err.find("are both shard 1/3 (runs 3..5 twice)") != std::string::npos);
  }
  SUBCASE("a damaged part is named") {
    std::string text = read_file(parts[1]);
    text[text.size() / 2] = text[text.size() / 2] == '1' ? '2' : '1';
    const std::string damaged = scratch_path("damaged.part");
    write_file(damaged, text);
    const Outcome o = vipars("merge '" + parts[0] + "' '" + damaged + "' '" + parts[2] + "'");
    CHECK(o.status == 2);
    CHECK(o.out.empty());
    CHECK(o.err.find("vipars merge: " + damaged + ": checksum mismatch") == 0);
    write_file(damaged, read_file(parts[1]).substr(0, 300));
    const Outcome cut = vipars("merge '" + parts[0] + "' '" + damaged + "' '" + parts[2] + "'");
    CHECK(cut.status == 2);
    CHECK(cut.err.find("vipars merge: " + damaged + ": not a complete part") == 0);
    std::remove(damaged.c_str());
  }
  SUBCASE("a part of another campaign (seed, grid) is named") {
    const std::string other = scratch_path("other.part");
    for (const std::string& change : {std::string("--seed 5"), std::string("--rmax-range 0.1:0.4:0.1")}) {
      std::string args = "validate '" + kMission + "' --world '" + kWorld + "' --trials 9 " +
                         (change.find("--seed") == 0 ? change : "--seed 4 " + change);
      REQUIRE(vipars(args + " --shard 1/3 --part '" + other + "'").status == 0);
      const Outcome o = vipars("merge" + quoted(parts, {0, 2}) + " '" + other + "'");
      CAPTURE(change);
      CHECK(o.status == 2);
      CHECK(o.err.find(other + ": not a part of the same campaign as " + parts[0]) != std::string::npos);
      CHECK(o.err.find(change.find("--seed") == 0 ? ": seed 5 vs 4" : ": grid") != std::string::npos);
    }
    std::remove(other.c_str());
  }
  SUBCASE("a part that is not there") {
    const Outcome o = vipars("merge '" + parts[0] + "' /nonexistent/shard.part");
    CHECK(o.status == 2);
    CHECK(o.err.find("/nonexistent/shard.part: cannot open") != std::string::npos);
  }
  remove_all(parts);
}

TEST_CASE("--shard and --part misuse is bad input naming the flag") {
  const std::string part = scratch_path("x.part");
  for (const auto& [args_text, message] : std::vector<std::pair<std::string, std::string>>{
           {"--shard 1/3", "--shard and --part: expected both or neither"},
           {"--part '" + part + "'", "--shard and --part: expected both or neither"},
           {"--shard 3/3 --part '" + part + "'", "--shard: expected I/N with 0 <= I < N"},
           {"--shard 0/10 --part '" + part + "'", "--shard: 10 shards of 9 runs"},
           {"--shard 0/3 --part '" + part + "' --json", "give --json and --csv to vipars merge"},
           {"--shard 0/3 --part /nonexistent/dir/x.part", "/nonexistent/dir/x.part.tmp: cannot write"}}) {
    const std::string args = args_text;  // a copy: CAPTURE's lambda cannot capture a binding on clang 14
    CAPTURE(args);
    const Outcome o = vipars(campaign(args));
    CHECK(o.status == 2);
    CHECK(o.err.find(message) != std::string::npos);
  }
  std::remove(part.c_str());
}

// The cross-check campaign sharded by mission (docs/cluster.md): merged, the
// same lines and summary as the unsharded campaign, and the same JSON but for
// each mission's seconds (timings, which differ between any two runs).
namespace {

nlohmann::json without_seconds(const std::string& text) {
  nlohmann::json j = nlohmann::json::parse(text);
  for (auto& m : j.at("missions")) m.erase("seconds");
  return j;
}

}  // namespace

TEST_CASE("a cross-check campaign sharded by mission merges into the unsharded campaign's results") {
  const std::string out = scratch_path("crosscheck-out");
  // Two one-robot missions whose verify is quick (seeds 7 and 8: 0.3 s of
  // CPU for the campaign in release), few runs and a small grid: the merge is
  // what is tested, and the test runs under ASan at -O0 in CI too.
  const std::string flags = "crosscheck --seeds 7:8 --robots 1:1 --runs 8 --calibration-runs 2 --tmax-points 5 "
                            "--rmax-points 5 --no-report --out '" + out + "'";
  const Outcome whole_text = vipars(flags);
  REQUIRE_MESSAGE(whole_text.status == 0, whole_text.err);
  const std::string whole_summary = read_file(out + "/summary.txt");
  // The campaign's document, as --json prints it (one document, written to
  // both): one whole campaign fewer to run.
  const std::string whole_json = read_file(out + "/crosscheck.json");
  REQUIRE(std::system(("rm -rf '" + out + "'").c_str()) == 0);
  std::vector<std::string> parts;
  for (int i = 0; i < 2; ++i) {
    parts.push_back(scratch_path("crosscheck-" + std::to_string(i) + ".part"));
    const Outcome o = vipars(flags + " --shard " + std::to_string(i) + "/2 --part '" + parts.back() + "'");
    REQUIRE_MESSAGE(o.status == 0, o.err);
  }
  const Outcome merged_text = vipars("merge" + quoted(parts, {1, 0}));
  CHECK(merged_text.status == 0);
  CHECK(merged_text.out == whole_text.out);
  CHECK(merged_text.err.find("vipars merge: merged 2 of 2 missions expected from 2 parts") != std::string::npos);
  CHECK(read_file(out + "/summary.txt") == whole_summary);
  const Outcome merged_json = vipars("merge" + quoted(parts, {0, 1}) + " --json");
  CHECK(merged_json.status == 0);
  CHECK(without_seconds(merged_json.out) == without_seconds(whole_json));

  const Outcome missing = vipars("merge" + quoted(parts, {1}));
  CHECK(missing.status == 2);
  CHECK(missing.err.find("missing 1 of 2 shards: shard 0/2 (missions 0..0); rerun it with --shard 0/2") !=
        std::string::npos);
  const Outcome mixed = vipars("merge" + quoted(parts, {0}) + " '" + make_parts("", 2)[1] + "'");
  CHECK(mixed.status == 2);
  remove_all(parts);
  REQUIRE(std::system(("rm -rf '" + out + "'").c_str()) == 0);
}
