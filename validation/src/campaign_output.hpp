#pragma once
// A validation campaign's result from its runs: the text report, the JSON
// document and the per-run CSV. The one code path of `vipars validate` and
// `vipars merge`, so a merged sharded campaign prints byte for byte what the
// unsharded one prints (docs/cluster.md).

#include <ostream>
#include <string>
#include <vector>

#include "p3at/team_sim/campaign_part.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/team_sim/team_run.hpp"

namespace p3at::vipars {

/// run_table's columns plus each robot's final phase ("finished", "aborted",
/// "running" when the run timed out).
std::string validation_csv_header(const std::vector<std::string>& robots);
std::string validation_csv_row(const team_sim::RunResult& run);
/// The header line and one line per run; false when the stream failed.
bool write_validation_csv(std::ostream& csv, const std::vector<std::string>& robots,
                          const std::vector<team_sim::RunResult>& runs);

/// Prints the report of `runs` (in run order) on stdout, text or JSON, for
/// the campaign `campaign` describes; returns the figures at its point.
team_sim::EmpiricalPoint print_campaign_report(const team_sim::CampaignHeader& campaign,
                                               const std::vector<team_sim::RunResult>& runs, bool json);

}  // namespace p3at::vipars
