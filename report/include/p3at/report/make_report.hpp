#pragma once
// `vipars report`'s run (docs/report.md): from two JSON documents, or running
// the verification and the validation campaign here, the data files, gnuplot
// figures, errors.json and index.html, and a summary line per error.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace p3at::vipars {

struct ReportFlags {
  // From files.
  std::string verify_file, validate_file;
  std::string verify_command, validate_command;
  // Run here.
  std::string mission_positional;
  std::uint64_t trials = 0;
  unsigned jobs = 0;
  std::uint64_t seed = 1;
  double timeout_s = 900.0;
  std::optional<double> tmax_s, rmax_m;
  std::string tmax_range, rmax_range;
  // Both.
  std::string mission_file, models_file, world_file;
  std::string out_dir, title, gnuplot = "gnuplot";
  bool no_plots = false;
  double region_low = 0.05, region_high = 0.95;
  std::vector<double> rmax_slices, tmax_slices;
};

/// Writes the report and prints the summary; returns the exit status
/// (p3at/common/vipars_exit.hpp): 0 every bound met, 1 one exceeded.
int run_report(ReportFlags flags);

}  // namespace p3at::vipars
