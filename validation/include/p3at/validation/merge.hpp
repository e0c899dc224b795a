#pragma once
// `vipars merge PART... [--json] [--csv FILE]` (docs/cluster.md): the parts a
// sharded validation campaign's shards wrote, combined into the result one
// unsharded `vipars validate` with the same seed prints, byte for byte.

#include <string>
#include <vector>

namespace p3at::vipars {

struct MergeOptions {
  std::vector<std::string> part_files;  ///< in any order
  bool json = false;
  std::string csv_file;
};

/// Reads, checks and merges the parts, prints the report (text or JSON) and
/// writes the CSV; returns the exit status (p3at/common/vipars_exit.hpp):
/// 2 for a damaged part, parts of different campaigns, a shard given twice
/// or missing (the message names the file or the shard to rerun), 3 when
/// every run of the campaign failed.
int run_merge(const MergeOptions& options);

}  // namespace p3at::vipars
