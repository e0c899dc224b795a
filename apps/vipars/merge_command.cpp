// vipars merge PART... [--json] [--csv FILE]
// The parts a sharded validation campaign's shards wrote (vipars validate
// --shard I/N --part FILE), combined into the result one unsharded
// `vipars validate` with the same seed prints, byte for byte: the same
// report code runs on the same runs in the same order. docs/cluster.md.

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "campaign_output.hpp"
#include "commands.hpp"
#include "p3at/team_sim/campaign_part.hpp"

namespace p3at::vipars {
namespace {

struct MergeOptions {
  std::vector<std::string> part_files;  // in any order
  bool json = false;
  std::string csv_file;
};

int refuse(const std::string& message) {
  std::fprintf(stderr, "vipars merge: %s\n", message.c_str());
  return kExitBadInput;
}

unsigned long long ull(std::uint64_t n) { return static_cast<unsigned long long>(n); }

// Exit 2 for a damaged part, parts of different campaigns, a shard given
// twice or missing (the message names the file, or the shard to rerun); 3
// when every run of the campaign failed, as for validate.
int merge(const MergeOptions& o) {
  if (o.part_files.empty()) return refuse("no parts given");
  std::ofstream csv;
  if (!o.csv_file.empty()) {
    csv.open(o.csv_file);
    if (!csv) return refuse("cannot write " + o.csv_file);
  }
  std::vector<team_sim::NamedPart> parts;
  std::uint64_t runs_read = 0;
  for (const auto& file : o.part_files) {
    auto part = team_sim::read_part_file(file);
    if (!part) return refuse(part.error().message);
    runs_read += part->runs.size();
    parts.push_back({file, std::move(part).value()});
  }
  const std::uint64_t expected = parts.front().part.header.trials;
  const std::size_t part_count = parts.size();
  auto merged = team_sim::merge_parts(std::move(parts));
  if (!merged) {
    std::fprintf(stderr, "vipars merge: %s\n", merged.error().message.c_str());
    std::fprintf(stderr, "vipars merge: merged %llu of %llu runs expected from %zu parts: refused, no result written\n",
                 ull(runs_read), ull(expected), part_count);
    return kExitBadInput;
  }
  std::fprintf(stderr, "vipars merge: merged %llu of %llu runs expected from %zu parts\n", ull(merged->runs.size()),
               ull(expected), part_count);
  if (csv.is_open() && !write_validation_csv(csv, merged->header.robots, merged->runs)) {
    return refuse("cannot write " + o.csv_file);
  }
  const team_sim::EmpiricalPoint point = print_campaign_report(merged->header, merged->runs, o.json);
  return point.failed_runs == point.runs ? kExitFailed : kExitOk;
}

}  // namespace

void register_merge(CLI::App& app, int& exit_status) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Merge the parts of a sharded validation campaign (validate --shard): the unsharded campaign's result");
  cmd->add_option("parts", o->part_files, "The shards' part files, in any order")->required();
  cmd->add_flag("--json", o->json, "Print the result as JSON (as vipars validate --json)");
  cmd->add_option("--csv", o->csv_file, "Write one row per run to this CSV file (as vipars validate --csv)");
  cmd->callback([o, &exit_status] { exit_status = merge(*o); });
}

}  // namespace p3at::vipars
