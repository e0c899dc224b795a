#pragma once
// Builds a report folder from a verification and a validation on the same
// grid: the data files, the gnuplot scripts and their PNG and SVG figures,
// errors.json and index.html (docs/report.md). Both `vipars report` modes end
// here.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/report/report_data.hpp"
#include "p3at/report/report_errors.hpp"

namespace p3at::vipars::report {

struct BuildOptions {
  std::string out_dir;              ///< created if missing
  std::string title;                ///< default: the mission's name
  std::string gnuplot = "gnuplot";  ///< program to render with
  bool render = true;               ///< false: scripts and data only (--no-plots)
  Thresholds thresholds;
  Limits limits;
  std::vector<double> rmax_slices;  ///< Fig. 12's Rmax values; empty: chosen (default_slices)
  std::vector<double> tmax_slices;  ///< Fig. 13's Tmax values; empty: chosen
  std::size_t slice_count = 4;
  std::vector<std::pair<std::string, std::string>> input_files;  ///< (role, path): hashed into the page
  std::vector<std::pair<std::string, std::string>> commands;     ///< (what, command line)
  std::vector<std::string> notes;                                ///< extra lines for the page
};

/// Called with one line per step done (for progress on stderr).
using ProgressLine = std::function<void(const std::string&)>;

/// Writes the report. Errors: documents that do not match (check_roles,
/// check_same_grid), a bad slice value, an unreadable input file, an
/// unwritable folder, or gnuplot failing (its own message included).
Result<Comparison> build_report(const Side& verification, const Side& validation, const BuildOptions& options,
                                const ProgressLine& progress = {});

}  // namespace p3at::vipars::report
