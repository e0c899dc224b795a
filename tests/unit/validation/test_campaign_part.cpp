// A shard's partial result (team_sim/campaign_part.hpp, docs/cluster.md):
// shards partition the runs of one campaign exactly; a part reads back to
// the same bits; a damaged part is refused naming its file (never merged
// into a wrong count); parts merge the same in any order; parts of another
// campaign, a shard given twice and a missing shard are refused with the
// file and the shard to rerun.

#include <doctest/doctest.h>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "p3at/team_sim/campaign.hpp"
#include "p3at/team_sim/campaign_part.hpp"
#include "p3at/team_sim/run_table.hpp"
#include "scratch.hpp"

namespace {

using p3at::team_sim::CampaignHeader;
using p3at::team_sim::CampaignPart;
using p3at::team_sim::NamedPart;
using p3at::team_sim::RunResult;
using p3at::team_sim::Shard;

constexpr std::uint64_t kSeed = 7;

CampaignHeader header(std::uint64_t trials) {
  CampaignHeader h;
  h.content_hash = std::string(64, 'a');
  h.seed = kSeed;
  h.trials = trials;
  h.timeout_s = 300.0;
  h.tmax_s = 200.0;
  h.rmax_m = 2.0;
  h.has_grid = true;
  h.tmax_axis = {190.0, 200.0, 210.0};
  h.rmax_axis = {1.0, 2.0, 3.1000000000000001};
  h.mission_name = "hand\tmade";  // a tab in a name must survive the tab-separated file
  h.threshold = 0.8;
  h.robots = {"robot1", "robot2"};
  h.mission_file = "missions/m.yaml";
  h.world_file = "worlds/w.yaml";
  return h;
}

// Run i of a hand-made campaign: successes at varied times and distances, a
// timeout, an abort whose reason holds the file's separators, and values
// that only survive a bit-exact number format (0.1 + 0.2, inf, nan).
RunResult hand_run(std::uint64_t i) {
  RunResult run;
  run.run = i;
  run.seed = p3at::team_sim::run_seed(kSeed, i);
  run.time_s = 185.0 + 2.5 * static_cast<double>(i % 11) + 0.1 + 0.2;
  run.closest_approach_m = 0.7 + 0.01 * static_cast<double>(i);
  run.outcome = "success";
  if (i % 7 == 3) {
    run.outcome = "timeout";
    run.time_s = 300.0;
  }
  if (i % 7 == 5) run.outcome = "aborted (robot2: stuck\tat a wall\nnear \\ the door)";
  for (std::uint64_t r = 0; r < 2; ++r) {
    p3at::team_sim::RobotResult robot;
    robot.name = r == 0 ? "robot1" : "robot2";
    robot.phase = run.outcome == "success" ? "finished" : (r == 1 && i % 7 == 5 ? "aborted" : "running");
    robot.dist_to_goal_m = 0.9 + 0.37 * static_cast<double>((i * (r + 3)) % 7);
    run.robots.push_back(robot);
  }
  if (i == 4) run.robots[1].dist_to_goal_m = std::numeric_limits<double>::quiet_NaN();
  if (i == 6) run.closest_approach_m = std::numeric_limits<double>::infinity();
  return run;
}

std::vector<RunResult> hand_runs(std::uint64_t first, std::uint64_t end) {
  std::vector<RunResult> runs;
  for (std::uint64_t i = first; i < end; ++i) runs.push_back(hand_run(i));
  return runs;
}

CampaignPart hand_part(std::uint64_t trials, Shard shard) {
  const auto range = p3at::team_sim::shard_runs(trials, shard);
  return p3at::team_sim::make_part(header(trials), shard, hand_runs(range.first, range.end));
}

std::string text_of(const CampaignPart& part) {
  std::ostringstream out;
  p3at::team_sim::write_part(out, part);
  return out.str();
}

bool same_bits(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

void check_same_runs(const std::vector<RunResult>& a, const std::vector<RunResult>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CAPTURE(i);
    CHECK(a[i].run == b[i].run);
    CHECK(a[i].seed == b[i].seed);
    CHECK(a[i].outcome == b[i].outcome);
    CHECK(same_bits(a[i].time_s, b[i].time_s));
    CHECK(same_bits(a[i].closest_approach_m, b[i].closest_approach_m));
    REQUIRE(a[i].robots.size() == b[i].robots.size());
    for (std::size_t r = 0; r < a[i].robots.size(); ++r) {
      CHECK(a[i].robots[r].name == b[i].robots[r].name);
      CHECK(a[i].robots[r].phase == b[i].robots[r].phase);
      CHECK(same_bits(a[i].robots[r].dist_to_goal_m, b[i].robots[r].dist_to_goal_m));
    }
  }
}

std::string error_of(const std::string& text, const std::string& source = "shard-1.part") {
  auto part = p3at::team_sim::parse_part(text, source);
  REQUIRE_FALSE(part.ok());
  return part.error().message;
}

// Replaces the first occurrence of `from` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// A part edited and then given a fresh checksum: what a writer with a bug
// would produce. The checks behind the checksum must still catch it.
std::string resealed(const std::string& text) {
  const auto end = text.rfind("end\t");
  REQUIRE(end != std::string::npos);
  const std::string body = text.substr(0, end);
  std::string runs_field = text.substr(end + 4);
  runs_field = runs_field.substr(0, runs_field.find('\t'));
  return body + "end\t" + runs_field + "\tblake2b-256\t" + p3at::team_sim::part_checksum(body) + "\n";
}

std::vector<NamedPart> named(const std::vector<CampaignPart>& parts, const std::vector<std::size_t>& order) {
  std::vector<NamedPart> out;
  for (std::size_t i : order) out.push_back({"shard-" + std::to_string(parts[i].shard.index) + ".part", parts[i]});
  return out;
}

}  // namespace

TEST_CASE("shards partition the runs of one campaign exactly") {
  for (std::uint64_t trials : {1ULL, 7ULL, 200ULL, 1'000'000ULL}) {
    for (std::uint64_t n : {1ULL, 2ULL, 3ULL, 4ULL, 7ULL, 64ULL}) {
      if (n > trials) continue;
      CAPTURE(trials);
      CAPTURE(n);
      std::uint64_t next = 0;
      for (std::uint64_t i = 0; i < n; ++i) {
        const auto r = p3at::team_sim::shard_runs(trials, Shard{i, n});
        CHECK(r.first == next);
        CHECK(r.end > r.first);                      // no empty shard
        CHECK(r.size() <= trials / n + 1);           // balanced within one run
        CHECK(r.size() >= trials / n);
        next = r.end;
      }
      CHECK(next == trials);
    }
  }
}

TEST_CASE("--shard I/N: good and bad") {
  auto s = p3at::team_sim::parse_shard("2/4");
  REQUIRE(s.ok());
  CHECK(s->index == 2);
  CHECK(s->count == 4);
  CHECK(p3at::team_sim::to_string(*s) == "2/4");
  CHECK(p3at::team_sim::parse_shard("0/1").ok());
  for (const char* bad : {"4/4", "1", "/4", "1/", "-1/4", "1/0", "a/4", "1/4x", "1/100001", ""}) {
    CAPTURE(bad);
    auto r = p3at::team_sim::parse_shard(bad);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("expected I/N") != std::string::npos);
  }
}

TEST_CASE("a part round-trips bit for bit, and writes the same bytes again") {
  const CampaignPart part = hand_part(40, Shard{1, 3});
  CHECK(part.range.first == 13);
  CHECK(part.range.end == 26);
  const std::string text = text_of(part);
  auto back = p3at::team_sim::parse_part(text, "p.part");
  REQUIRE_MESSAGE(back.ok(), back.error().message);
  CHECK(back->shard.index == 1);
  CHECK(back->shard.count == 3);
  CHECK(back->range.first == 13);
  CHECK(back->range.end == 26);
  CHECK_FALSE(p3at::team_sim::campaign_difference(part.header, back->header).has_value());
  CHECK(back->header.mission_name == "hand\tmade");
  CHECK(back->header.mission_file == "missions/m.yaml");
  CHECK(back->header.rmax_axis[2] == 3.1000000000000001);
  CHECK(back->counts == part.counts);
  check_same_runs(back->runs, part.runs);
  CHECK(text_of(*back) == text);
  // The counts are real: a failed run is counted, and the grid's joint
  // cell at the point equals the point's joint count.
  CHECK(part.counts.runs == 13);
  CHECK(part.counts.failed > 0);
  CHECK(part.counts.grid_joint[1 * 3 + 1] == part.counts.joint);
}

TEST_CASE("a part written to a file reads back; a missing file is named") {
  const std::string path = p3at::test::scratch_path("campaign.part");
  const CampaignPart part = hand_part(40, Shard{2, 3});
  REQUIRE(p3at::team_sim::write_part_file(path, part).ok());
  auto back = p3at::team_sim::read_part_file(path);
  REQUIRE_MESSAGE(back.ok(), back.error().message);
  check_same_runs(back->runs, part.runs);
  std::remove(path.c_str());
  auto missing = p3at::team_sim::read_part_file(path + ".nope");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().message.find(path + ".nope: cannot open") == 0);
}

TEST_CASE("a damaged part is refused, naming the file, never read as a wrong count") {
  const std::string text = text_of(hand_part(40, Shard{1, 3}));

  SUBCASE("one digit changed: checksum") {
    const std::string changed = replaced(text, "run\t20\t", "run\t21\t");  // run 20's index
    CHECK(error_of(changed).find("shard-1.part: checksum mismatch") == 0);
  }
  SUBCASE("cut short") {
    CHECK(error_of(text.substr(0, text.size() / 2)).find("shard-1.part: not a complete part") == 0);
    CHECK(error_of(text.substr(0, text.size() - 1)).find("shard-1.part: not a complete part") == 0);
    CHECK(error_of("").find("shard-1.part: not a complete part") == 0);
  }
  SUBCASE("a last run line dropped and the end line kept: checksum") {
    const auto end = text.rfind("run\t25\t");
    const auto end_line = text.rfind("end\t");
    CHECK(error_of(text.substr(0, end) + text.substr(end_line)).find("checksum mismatch") != std::string::npos);
  }
  SUBCASE("behind a valid checksum: counts that disagree with the runs") {
    const std::string forged = resealed(replaced(text, "counts\t13\t", "counts\t14\t"));
    const std::string e = error_of(forged);
    CHECK(e.find("shard-1.part: its counts disagree with its runs (runs: 14 vs 13") == 0);
  }
  SUBCASE("behind a valid checksum: a run's seed not this campaign's") {
    const std::string seed = std::to_string(p3at::team_sim::run_seed(kSeed, 14));
    const std::string forged = resealed(replaced(text, "\t" + seed + "\t", "\t12345\t"));
    const std::string e = error_of(forged);
    CHECK(e.find("shard-1.part:") == 0);
    CHECK(e.find("run 14: seed 12345 is not this campaign's") != std::string::npos);
  }
  SUBCASE("behind a valid checksum: a bad number names the line and what was expected") {
    const std::string forged = resealed(replaced(text, "timeout_s\t300", "timeout_s\tthree hundred"));
    CHECK(error_of(forged) == "shard-1.part:7: timeout_s: expected a number, got 'three hundred'");
  }
  SUBCASE("behind a valid checksum: runs out of order") {
    const auto a = text.find("run\t14\t");
    const auto b = text.find("run\t15\t");
    const auto c = text.find("run\t16\t");
    std::string swapped = text.substr(0, a) + text.substr(b, c - b) + text.substr(a, b - a) + text.substr(c);
    CHECK(error_of(resealed(swapped)).find("expected run 14, got run 15") != std::string::npos);
  }
  SUBCASE("a version 1 part (distances where the last trigger fired, not at rest): refused, saying why") {
    // Written by a vipars before final positions were recorded at rest; its
    // checksum is valid, its runs well formed: only the version tells.
    REQUIRE(text.rfind("vipars-validation-part\t2\n", 0) == 0);
    const std::string old = resealed(replaced(text, "vipars-validation-part\t2\n", "vipars-validation-part\t1\n"));
    const std::string e = error_of(old);
    CHECK(e.find("shard-1.part:1: part format version 1, this vipars reads version 2") == 0);
    CHECK(e.find("not where it came to rest") != std::string::npos);
    CHECK(e.find("rerun its shard") != std::string::npos);
    // Another unknown version is refused too, without that reason.
    const std::string future = resealed(replaced(text, "vipars-validation-part\t2\n", "vipars-validation-part\t3\n"));
    CHECK(error_of(future) == "shard-1.part:1: part format version 3, this vipars reads version 2");
  }
  SUBCASE("behind a valid checksum: a shard whose runs are not its share") {
    const std::string forged = resealed(replaced(text, "runs\t13\t26", "runs\t13\t27"));
    CHECK(error_of(forged).find("shard-1.part:6: runs: shard 1/3 of 40 trials is runs 13 26") == 0);
  }
}

TEST_CASE("parts merge the same in any order, into the whole campaign's runs and counts") {
  constexpr std::uint64_t kTrials = 40;
  std::vector<CampaignPart> parts;
  for (std::uint64_t i = 0; i < 3; ++i) parts.push_back(hand_part(kTrials, Shard{i, 3}));
  const auto whole = hand_runs(0, kTrials);
  const auto whole_counts = p3at::team_sim::count_runs(header(kTrials), whole);
  std::vector<std::size_t> order{0, 1, 2};
  do {
    CAPTURE(order[0]);
    CAPTURE(order[1]);
    auto merged = p3at::team_sim::merge_parts(named(parts, order));
    REQUIRE_MESSAGE(merged.ok(), merged.error().message);
    check_same_runs(merged->runs, whole);
    CHECK(merged->counts == whole_counts);
    CHECK(merged->shard_count == 3);
    CHECK(merged->header.mission_file == "missions/m.yaml");
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST_CASE("merge refuses parts of another campaign, naming the file and the difference") {
  std::vector<CampaignPart> parts;
  for (std::uint64_t i = 0; i < 3; ++i) parts.push_back(hand_part(40, Shard{i, 3}));
  const auto refusal = [&](auto&& change) {
    auto copy = parts;
    change(copy[2]);
    auto merged = p3at::team_sim::merge_parts(named(copy, {0, 1, 2}));
    REQUIRE_FALSE(merged.ok());
    return merged.error().message;
  };
  CHECK(refusal([](CampaignPart& p) { p.header.content_hash = std::string(64, 'b'); })
            .find("shard-2.part: not a part of the same campaign as shard-0.part: mission/world content hash") == 0);
  CHECK(refusal([](CampaignPart& p) { p.header.seed = 8; }) ==
        "shard-2.part: not a part of the same campaign as shard-0.part: seed 8 vs 7");
  CHECK(refusal([](CampaignPart& p) { p.header.rmax_axis[0] = 1.5; })
            .find("shard-2.part: not a part of the same campaign as shard-0.part: grid") == 0);
  CHECK(refusal([](CampaignPart& p) { p.header.timeout_s = 900; }).find("timeout 900 s vs 300 s") != std::string::npos);
  CHECK(refusal([](CampaignPart& p) { p.shard.count = 4; }).find("shard-2.part: shard 2/4 of a campaign cut into 4") == 0);
  // The paths are not the campaign: a part run from another folder merges.
  auto moved = parts;
  moved[1].header.mission_file = "/elsewhere/m.yaml";
  CHECK(p3at::team_sim::merge_parts(named(moved, {0, 1, 2})).ok());
}

TEST_CASE("merge refuses a shard given twice and names a missing shard to rerun") {
  std::vector<CampaignPart> parts;
  for (std::uint64_t i = 0; i < 4; ++i) parts.push_back(hand_part(40, Shard{i, 4}));
  auto twice = named(parts, {0, 1, 2, 3});
  twice.push_back({"rerun/shard-2.part", parts[2]});
  auto dup = p3at::team_sim::merge_parts(twice);
  REQUIRE_FALSE(dup.ok());
  CHECK(dup.error().message.find("are both shard 2/4 (runs 20..29 twice)") != std::string::npos);
  CHECK(dup.error().message.find("rerun/shard-2.part") != std::string::npos);

  auto one_missing = p3at::team_sim::merge_parts(named(parts, {3, 0, 1}));
  REQUIRE_FALSE(one_missing.ok());
  CHECK(one_missing.error().message ==
        "missing 1 of 4 shards: shard 2/4 (runs 20..29); rerun it with --shard 2/4 (the command line otherwise the "
        "same)");
  auto two_missing = p3at::team_sim::merge_parts(named(parts, {1, 2}));
  REQUIRE_FALSE(two_missing.ok());
  CHECK(two_missing.error().message.find("missing 2 of 4 shards: shard 0/4 (runs 0..9), shard 3/4 (runs 30..39)") ==
        0);
  CHECK_FALSE(p3at::team_sim::merge_parts({}).ok());
}

TEST_CASE("shards of a real campaign are exactly the unsharded campaign's runs") {
  const std::string dir = std::string(P3AT_SOURCE_DIR) + "/examples/relay/";
  const p3at::team_sim::TeamScenario scenario(p3at::mission::load_mission_file(dir + "mission.yaml"),
                                               p3at::sim::load_world_file(dir + "world.yaml"));
  p3at::team_sim::CampaignOptions options;
  options.runs = 7;
  options.seed = 3;
  options.jobs = 2;
  const auto whole = p3at::team_sim::run_campaign(scenario, options);
  std::vector<RunResult> sharded;
  for (std::uint64_t i = 0; i < 3; ++i) {
    const auto range = p3at::team_sim::shard_runs(options.runs, Shard{i, 3});
    auto shard_options = options;
    shard_options.first_run = range.first;
    shard_options.runs = range.size();
    for (auto& run : p3at::team_sim::run_campaign(scenario, shard_options)) sharded.push_back(std::move(run));
  }
  REQUIRE(sharded.size() == whole.size());
  for (std::size_t i = 0; i < whole.size(); ++i) {
    CHECK(sharded[i].run == i);
    CHECK(p3at::team_sim::csv_row(sharded[i]) == p3at::team_sim::csv_row(whole[i]));
    CHECK(same_bits(sharded[i].time_s, whole[i].time_s));
  }
}
