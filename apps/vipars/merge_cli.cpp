// vipars merge PART... [--json] [--csv FILE]
// The flags; the merge is p3at_validation's run_merge() for a validation
// campaign's parts, p3at_crosscheck's merge_crosscheck() for a cross-check
// campaign's (told apart by the first part's first line; docs/cluster.md).

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "p3at/crosscheck/run.hpp"
#include "p3at/crosscheck/shard_part.hpp"
#include "p3at/validation/merge.hpp"

namespace p3at::vipars {
namespace {

bool first_is_crosscheck_part(const std::vector<std::string>& files) {
  if (files.empty()) return false;
  std::ifstream in(files.front(), std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return crosscheck::is_crosscheck_part(head);
}

int merge(const MergeOptions& o) {
  if (!first_is_crosscheck_part(o.part_files)) return run_merge(o);
  if (!o.csv_file.empty()) {
    std::fprintf(stderr, "vipars merge: --csv: a cross-check campaign's per-run CSVs are in its missions' folders\n");
    return kExitBadInput;
  }
  return crosscheck::merge_crosscheck(o.part_files, o.json);
}

}  // namespace

void register_merge(CLI::App& app, int& exit_status) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Merge the parts of a sharded validation or cross-check campaign (--shard): the unsharded campaign's result");
  cmd->add_option("parts", o->part_files, "The shards' part files, in any order")->required();
  cmd->add_flag("--json", o->json, "Print the result as JSON (as vipars validate --json)");
  cmd->add_option("--csv", o->csv_file, "Write one row per run to this CSV file (as vipars validate --csv)");
  cmd->callback([o, &exit_status] { exit_status = merge(*o); });
}

}  // namespace p3at::vipars
