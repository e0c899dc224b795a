#pragma once
/// `vipars crosscheck` (docs/crosscheck.md): the campaign over generated
/// missions and folders of missions, its lines, summary, JSON, progress,
/// report and the CI gate's baseline check. The binary only parses flags.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/crosscheck/campaign.hpp"
#include "p3at/team_sim/campaign_part.hpp"

namespace p3at::crosscheck {

struct CrosscheckRun {
  std::optional<std::uint64_t> first_seed, last_seed;   ///< generated missions first..last
  std::size_t min_robots = 1, max_robots = 6;
  std::vector<std::string> folders;                     ///< mission folders, or folders of them
  bool shipped_models = false;                          ///< use a folder's models.yaml instead of calibrating
  CampaignOptions campaign;
  bool json = false;                                    ///< stdout: the JSON document instead of text
  bool report = true;                                   ///< distribution figures, index.html, failing missions' pages
  std::string baseline;                                 ///< check every mission against this file (CI gate)
  std::string write_baseline;                           ///< record this campaign's errors (+ margin) here
  double baseline_margin = 0.03;
  std::optional<team_sim::Shard> shard;                 ///< only this shard's missions, written as a part
  std::string part_file;                                ///< with shard: where (docs/cluster.md)
  /// Instead of running: the summary, JSON and report of the missions a
  /// campaign (or several) already wrote to DIR/missions.jsonl, e.g. one
  /// stopped part-way. campaign.out_dir is that DIR.
  bool from_results = false;
};

/// Exit statuses: 0 done (and, with a baseline, every mission within it);
/// 1 a mission worse than its baseline, or missing from it; 2 bad input;
/// 3 a mission could not be cross-checked or the output not written.
/// With a shard: only its missions, their lines, and the part; exit 0 once
/// the part is written (the summary, JSON, report and baseline are merge's).
int run_crosscheck(const CrosscheckRun& run);

/// `vipars merge` of a sharded campaign's parts: the lines, summary, JSON,
/// report and baseline check of the unsharded campaign, with its exit
/// statuses; 2 for parts that do not make one whole campaign (the message
/// names the file, or the shard to rerun).
int merge_crosscheck(const std::vector<std::string>& part_files, bool json);

}  // namespace p3at::crosscheck
