#pragma once
/// A cross-check campaign sharded by mission (docs/cluster.md): shard I of N
/// cross-checks missions [floor(I*M/N), floor((I+1)*M/N)) of the campaign's
/// M missions (in the order the campaign lists them) and writes a part: the
/// campaign's identity (a hash over every mission's files and the options
/// that change results), the unsharded command line, and one JSON line per
/// mission result (mission_result_json), closed by a BLAKE2b checksum line.
/// Merging the parts gives back the campaign's results in order, so the
/// lines, the summary, the JSON and the report come out as the unsharded
/// campaign's (the per-mission seconds are the shards' own timings).

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "p3at/common/result.hpp"
#include "p3at/crosscheck/campaign.hpp"
#include "p3at/team_sim/campaign_part.hpp"

namespace p3at::crosscheck {

/// What every part of one campaign shares.
struct CrosscheckPartHeader {
  std::string identity;            ///< campaign_identity(): 64 hex digits
  std::string command;             ///< the unsharded campaign's command line (printed by the merge)
  std::vector<std::string> names;  ///< every mission of the campaign, in order
  team_sim::Shard shard;
  team_sim::RunRange missions;     ///< this shard's missions, indices into names
  // What the merge writes, as the unsharded campaign would (not compared:
  // they change no result): shard 0's are used.
  std::string out_dir, gnuplot = "gnuplot", baseline, write_baseline;
  bool report = true;
  double baseline_margin = 0.03;
  std::uint64_t runs_per_mission = 0, seed = 0;  ///< as the campaign's JSON gives them (also in the identity)
};

struct CrosscheckPart {
  CrosscheckPartHeader header;
  std::vector<MissionResult> results;  ///< missions.first .. missions.end - 1
};

/// BLAKE2b-256 over the missions (names, files, generator seeds) and the
/// options that change a result (runs, seed, calibration, grid points).
std::string campaign_identity(const std::vector<MissionInput>& inputs, const CampaignOptions& options);

void write_crosscheck_part(std::ostream& out, const CrosscheckPart& part);
Status write_crosscheck_part_file(const std::string& path, const CrosscheckPart& part);
/// True when `text` starts like a cross-check part (vipars merge tells the kinds apart by it).
bool is_crosscheck_part(std::string_view text);
Result<CrosscheckPart> parse_crosscheck_part(std::string_view text, const std::string& source);
Result<CrosscheckPart> read_crosscheck_part_file(const std::string& path);

/// MissionResult from mission_result_json()'s document (the inverse;
/// null numbers come back as NaN). Throws std::exception on a wrong shape.
MissionResult mission_result_from_json(const nlohmann::ordered_json& j);

struct NamedCrosscheckPart {
  std::string file;
  CrosscheckPart part;
};

/// The campaign's results in mission order, and its command line. Refuses,
/// naming the file, a part of another campaign, a shard given twice and a
/// missing shard (saying which to rerun), as team_sim::merge_parts does.
struct MergedCrosscheck {
  CrosscheckPartHeader header;  ///< shard 0's (its outputs are the merge's)
  std::string command;
  std::vector<MissionResult> results;
  std::size_t parts = 0;
};
Result<MergedCrosscheck> merge_crosscheck_parts(std::vector<NamedCrosscheckPart> parts);

}  // namespace p3at::crosscheck
