// vipars merge PART... [--json] [--csv FILE]
// The flags; the merge is p3at_validation's run_merge() (docs/cluster.md).

#include <memory>

#include "commands.hpp"
#include "p3at/validation/merge.hpp"

namespace p3at::vipars {

void register_merge(CLI::App& app, int& exit_status) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Merge the parts of a sharded validation campaign (validate --shard): the unsharded campaign's result");
  cmd->add_option("parts", o->part_files, "The shards' part files, in any order")->required();
  cmd->add_flag("--json", o->json, "Print the result as JSON (as vipars validate --json)");
  cmd->add_option("--csv", o->csv_file, "Write one row per run to this CSV file (as vipars validate --csv)");
  cmd->callback([o, &exit_status] { exit_status = run_merge(*o); });
}

}  // namespace p3at::vipars
