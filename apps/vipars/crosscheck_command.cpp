// vipars crosscheck [--seeds A:B [--robots A:B]] [--missions DIR...] [--runs N] ...
// verify against validate on missions nobody tuned the verifier to
// (docs/crosscheck.md). Flags only; the campaign is p3at_crosscheck.

#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "p3at/crosscheck/run.hpp"
#include "p3at/team_sim/campaign_part.hpp"

namespace p3at::vipars {
namespace {

struct CrosscheckFlags {
  std::string shard;
  std::string seeds;
  std::string robots = "1:6";
  crosscheck::CrosscheckRun run;
  bool no_report = false;
};

bool parse_pair(const std::string& text, unsigned long long& a, unsigned long long& b) {
  char tail = 0;
  return std::sscanf(text.c_str(), "%llu:%llu%c", &a, &b, &tail) == 2 && a <= b;
}

int run(CrosscheckFlags f) {
  if (!f.seeds.empty()) {
    unsigned long long a = 0, b = 0;
    if (!parse_pair(f.seeds, a, b)) {
      std::fprintf(stderr, "vipars crosscheck: --seeds: expected A:B with A <= B, got '%s'\n", f.seeds.c_str());
      return kExitBadInput;
    }
    f.run.first_seed = a;
    f.run.last_seed = b;
  }
  unsigned long long lo = 0, hi = 0;
  if (!parse_pair(f.robots, lo, hi) || lo < 1 || hi > 6) {
    std::fprintf(stderr, "vipars crosscheck: --robots: expected A:B with 1 <= A <= B <= 6, got '%s'\n", f.robots.c_str());
    return kExitBadInput;
  }
  f.run.min_robots = lo;
  f.run.max_robots = hi;
  f.run.report = !f.no_report;
  if (f.shard.empty() != f.run.part_file.empty()) {
    std::fprintf(stderr, "vipars crosscheck: --shard and --part: expected both or neither\n");
    return kExitBadInput;
  }
  if (!f.shard.empty()) {
    auto shard = team_sim::parse_shard(f.shard);
    if (!shard) {
      std::fprintf(stderr, "vipars crosscheck: --shard: %s\n", shard.error().message.c_str());
      return kExitBadInput;
    }
    if (f.run.json) {
      std::fprintf(stderr, "vipars crosscheck: --shard: a shard writes its part only; give --json to vipars merge\n");
      return kExitBadInput;
    }
    f.run.shard = *shard;
  }
  return crosscheck::run_crosscheck(f.run);
}

}  // namespace

void register_crosscheck(CLI::App& app, int& exit_status) {
  auto f = std::make_shared<CrosscheckFlags>();
  crosscheck::CrosscheckRun& r = f->run;
  r.campaign.out_dir = "crosscheck-out";
  CLI::App* sub = app.add_subcommand(
      "crosscheck",
      "Verify against validate on generated missions and folders of missions: calibrate from each world, verify and "
      "validate on one grid, score (docs/crosscheck.md)");
  sub->add_option("--seeds", f->seeds, "Generated missions for seeds A:B (vipars generate)");
  sub->add_option("--robots", f->robots, "Team sizes of the generated missions, A:B within 1:6 (default 1:6)");
  sub->add_option("--missions", r.folders,
                  "Folders holding mission.yaml and world.yaml, or folders of such folders")
      ->expected(1, -1);
  sub->add_flag("--shipped-models", r.shipped_models, "Use a folder's models.yaml instead of calibrating from its world");
  sub->add_option("--runs", r.campaign.runs, "Validation runs per mission (default 1000)")->check(CLI::Range(1, 1000000));
  sub->add_option("--seed", r.campaign.seed, "Campaign seed: each mission's validation seed derives from it (default 1)");
  sub->add_option("--jobs", r.campaign.jobs, "Validation threads (default: all cores); results never depend on it")
      ->check(CLI::Range(0, 1024));
  sub->add_option("--calibration-runs", r.campaign.calibration_runs, "Calibration runs per robot (default 20)")
      ->check(CLI::Range(2, 100000));
  sub->add_option("--tmax-points", r.campaign.tmax_points, "At most this many Tmax values (default 41)")->check(CLI::Range(3, 1000));
  sub->add_option("--rmax-points", r.campaign.rmax_points, "At most this many Rmax values (default 31)")->check(CLI::Range(3, 1000));
  sub->add_option("--out", r.campaign.out_dir, "The campaign's folder: index.html, crosscheck.json, missions/NAME/ (default crosscheck-out)");
  sub->add_flag("--json", r.json, "Print the campaign's JSON instead of text");
  sub->add_flag("--no-report", f->no_report, "No figures, pages or index.html");
  sub->add_flag("--from-results", r.from_results,
                "Run nothing: the summary, JSON and report of the missions already in --out DIR/missions.jsonl "
                "(a campaign stopped part-way, or several appended)");
  sub->add_flag("--reuse-runs", r.campaign.reuse_runs,
                "Take each mission's validation runs from --out DIR/missions/NAME/runs.part when they were made from "
                "the same files, seed, runs and timeout (re-scores a verifier change without re-simulating)");
  sub->add_flag("--runs-only", r.campaign.runs_only,
                "Only make (or keep) each mission's validation runs in --out DIR/missions/NAME/runs.part: no "
                "calibration, verification or scores (score them later with --reuse-runs)");
  sub->add_option("--gnuplot", r.campaign.gnuplot, "gnuplot to draw with (default gnuplot)");
  sub->add_option("--baseline", r.baseline, "Fail (exit 1) when a mission is worse than this file allows (the CI gate)");
  sub->add_option("--write-baseline", r.write_baseline, "Record this campaign's errors, plus a margin, as a baseline");
  sub->add_option("--baseline-margin", r.baseline_margin, "Margin added to generated missions' errors (default 0.03)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_option("--shard", f->shard,
                  "Cross-check only shard I of N's missions (I from 0), written as a part for vipars merge (docs/cluster.md)");
  sub->add_option("--part", r.part_file, "With --shard: write the shard's part here");
  sub->callback([f, &exit_status] { exit_status = run(*f); });
}

}  // namespace p3at::vipars
