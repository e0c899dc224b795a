#pragma once
/// The campaign's report (docs/crosscheck.md): the distribution of the errors
/// over the missions (histogram and CDF, gnuplot PNG and SVG), an index.html
/// listing every mission worst first, and for each failing mission its
/// Figs. 9-14 page made by `vipars report`'s own library.

#include <string>
#include <vector>

#include "p3at/crosscheck/campaign.hpp"
#include "p3at/crosscheck/result_json.hpp"

namespace p3at::crosscheck {

struct ReportOptions {
  std::string out_dir;                 ///< the campaign's folder (index.html goes here)
  std::string gnuplot = "gnuplot";
  std::size_t max_pages = 50;          ///< failing missions given a page, worst first
  std::string command;                 ///< the campaign's command line, for the page
};

/// A mission that fails: outside a bound even with the 1 % shift, or with an over-confident GO cell.
bool mission_fails(const MissionResult& result, const Bounds& bounds);

/// Writes the figures, the pages and index.html. Returns one line per
/// problem (gnuplot missing, a page that could not be made); the rest is
/// still written.
std::vector<std::string> write_campaign_report(const std::vector<MissionResult>& results, const CampaignSummary& summary,
                                               const Bounds& bounds, const ReportOptions& options);

}  // namespace p3at::crosscheck
