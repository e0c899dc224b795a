#pragma once
/// A shard of a validation campaign and the partial result it writes
/// (docs/cluster.md): campaigns too big for one machine run as N shards, one
/// per cluster task, and `vipars merge` combines their parts into exactly the
/// result one unsharded campaign with the same seed gives.
///
/// Shard I of N makes runs [floor(I*T/N), floor((I+1)*T/N)) of a T-run
/// campaign, each with the seed it has in the unsharded campaign
/// (run_seed(S, i)), so the shards partition its runs exactly.
///
/// A part holds what the merged result needs and what proves it belongs:
/// the campaign it is a shard of (content hash of the mission and world
/// files, seed, trials, criteria point, grid, timeout), the per-cell counts
/// (the sufficient statistics of every probability), and one record per run
/// at full precision (the CSV's columns: outcome with its reason, completion
/// time, every robot's phase and true distance), from which the merged CSV
/// and the means and standard deviations are printed by the same code as
/// for an unsharded campaign. A BLAKE2b-256 checksum closes the file;
/// reading recomputes it, checks every run's index and seed, and recounts
/// the cells from the runs, so a damaged part is refused (naming the file
/// and line) rather than merged into a wrong count.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/team_sim/part_file.hpp"
#include "p3at/team_sim/run_result.hpp"

namespace p3at::team_sim {

/// Shard `index` of `count`, 0 <= index < count (Slurm's array task ids 0..N-1).
struct Shard {
  std::uint64_t index = 0;
  std::uint64_t count = 1;
};
inline constexpr std::uint64_t kMaxShards = 100'000;

/// Parses "I/N" (0 <= I < N <= kMaxShards); the error says what was expected.
Result<Shard> parse_shard(std::string_view text);
std::string to_string(const Shard& shard);  ///< "I/N"

/// Run indices [first, end).
struct RunRange {
  std::uint64_t first = 0;
  std::uint64_t end = 0;
  std::uint64_t size() const { return end - first; }
};
/// The runs of a `trials`-run campaign that shard `shard` makes.
RunRange shard_runs(std::uint64_t trials, const Shard& shard);
/// "first..last" (inclusive), or "none".
std::string range_text(const RunRange& range);

/// A part's file and its shard, for shard_set_problem.
struct FileShard {
  std::string file;
  Shard shard;
};
/// What is wrong with a set of parts' shards, sorted by index and all of one
/// count N, of a campaign of `items` runs or missions (`counted` names them):
/// "A and B are both shard I/N (<counted> ... twice): give each shard once" or
/// "missing K of N shards: shard I/N (<counted> ...), ...; rerun it with
/// --shard I/N (...)"; nothing when each shard is there once. Shared by
/// validation and cross-check merges.
std::optional<std::string> shard_set_problem(const std::vector<FileShard>& sorted, std::uint64_t items,
                                             std::string_view counted);

/// What every part of one campaign shares. Two parts are of the same
/// campaign when everything here but the descriptive fields is equal.
struct CampaignHeader {
  std::string content_hash;            ///< 64 hex digits over the mission and world files' bytes
  std::uint64_t seed = 1;
  std::uint64_t trials = 0;            ///< runs of the whole (unsharded) campaign
  double timeout_s = 900.0;
  double tmax_s = 0.0, rmax_m = 0.0;   ///< the criterion point
  bool has_grid = false;               ///< a --tmax-range or --rmax-range was given
  std::vector<double> tmax_axis, rmax_axis;  ///< the grid's axes (the point's value when not a range)
  double region_low = 0.05, region_high = 0.95;
  // Descriptive: the same whenever content_hash is (name, threshold and
  // robots come from the mission file), or not part of the result (paths).
  std::string mission_name;
  double threshold = 0.0;
  std::vector<std::string> robots;     ///< the mission's robots, in its order
  std::string mission_file, world_file;  ///< as given on the command line
};

/// The first field in which two parts' campaigns differ ("mission content
/// hash", "seed", "trials", "grid", ...) with both values, or nothing.
std::optional<std::string> campaign_difference(const CampaignHeader& a, const CampaignHeader& b);

/// The sufficient statistics of every probability the report gives: counts
/// at the criterion point and in every grid cell.
struct PartCounts {
  std::uint64_t runs = 0;
  std::uint64_t failed = 0;
  std::uint64_t time = 0, radius = 0, joint = 0;  ///< at the point
  std::vector<std::uint64_t> robot_radius;        ///< at the point, per robot
  std::vector<std::uint64_t> grid_time;           ///< per tmax_axis value
  std::vector<std::uint64_t> grid_radius;         ///< per rmax_axis value
  std::vector<std::uint64_t> grid_joint;          ///< [tmax][rmax], row-major
  bool operator==(const PartCounts&) const = default;
};
/// Counts `runs` on the header's point and grid (the same code as the report's figures).
PartCounts count_runs(const CampaignHeader& header, const std::vector<RunResult>& runs);
/// Cell-by-cell sum; both must have the header's shape.
void add_counts(PartCounts& total, const PartCounts& part);
/// The first count in which they differ, as "name: a vs b", or nothing.
std::optional<std::string> counts_difference(const PartCounts& a, const PartCounts& b);

struct CampaignPart {
  CampaignHeader header;
  Shard shard;
  RunRange range;
  PartCounts counts;
  std::vector<RunResult> runs;  ///< runs range.first .. range.end - 1, in order
};

/// Builds a part from a shard's runs (counts computed here).
CampaignPart make_part(CampaignHeader header, const Shard& shard, std::vector<RunResult> runs);

/// The part's text (docs/cluster.md), checksum line included.
void write_part(std::ostream& out, const CampaignPart& part);
/// Writes `path` whole or not at all (a temporary file renamed into place),
/// so a shard killed while writing leaves no part that looks finished.
Status write_part_file(const std::string& path, const CampaignPart& part);

/// Parses a part; `source` names it in errors ("file:line: expected ...").
Result<CampaignPart> parse_part(std::string_view text, const std::string& source);
Result<CampaignPart> read_part_file(const std::string& path);

/// A part and the file it came from (for error messages).
struct NamedPart {
  std::string file;
  CampaignPart part;
};

struct MergedCampaign {
  CampaignHeader header;        ///< shard 0's (its paths are the result's)
  PartCounts counts;            ///< summed over the parts
  std::vector<RunResult> runs;  ///< every run, in index order
  std::uint64_t shard_count = 0;
};

/// Combines the parts of one campaign, given in any order. Refuses, naming
/// the file: a part of another campaign (and in what it differs), the same
/// shard twice (overlapping runs), a different shard count; and a missing
/// shard, saying which to rerun ("missing shard 2/4 (runs 100..149): rerun
/// it with --shard 2/4").
Result<MergedCampaign> merge_parts(std::vector<NamedPart> parts);

}  // namespace p3at::team_sim
