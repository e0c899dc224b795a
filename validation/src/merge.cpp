// vipars merge PART... [--json] [--csv FILE] (the flags:
// apps/vipars/merge_cli.cpp; the merge: here). docs/cluster.md.

#include "p3at/validation/merge.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <utility>

#include "campaign_output.hpp"
#include "p3at/common/vipars_exit.hpp"
#include "p3at/team_sim/campaign_part.hpp"

namespace p3at::vipars {
namespace {

int refuse(const std::string& message) {
  std::fprintf(stderr, "vipars merge: %s\n", message.c_str());
  return kExitBadInput;
}

unsigned long long ull(std::uint64_t n) { return static_cast<unsigned long long>(n); }

}  // namespace

int run_merge(const MergeOptions& o) {
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
  std::fprintf(stderr, "vipars merge: merged %llu of %llu runs expected from %zu parts\n",
               ull(merged->runs.size()), ull(expected), part_count);
  if (csv.is_open() && !write_validation_csv(csv, merged->header.robots, merged->runs)) {
    return refuse("cannot write " + o.csv_file);
  }
  const team_sim::EmpiricalPoint point = print_campaign_report(merged->header, merged->runs, o.json);
  return point.failed_runs == point.runs ? kExitFailed : kExitOk;
}

}  // namespace p3at::vipars
