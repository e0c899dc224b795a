#pragma once
// The report's data files: one gnuplot-readable .dat per figure, written
// from the two documents without any rounding (every number with 17
// significant digits, so it reads back as the very double the JSON held).
// The figures' scripts (report_plots.hpp) plot these files and nothing else,
// so what a figure shows is what the data files say. Columns: docs/report.md.

#include <cstddef>
#include <string>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/report/report_data.hpp"
#include "p3at/report/report_errors.hpp"

namespace p3at::vipars::report {

/// Which axis values the slice figures show: Fig. 12 plots P(joint) against
/// Tmax at the `rmax` indices, Fig. 13 against Rmax at the `tmax` indices.
struct Slices {
  std::vector<std::size_t> rmax;
  std::vector<std::size_t> tmax;
};

/// `count` indices spread evenly over the part of the axis where the curves
/// rise (from the first point where either side reaches 0.02 to the first
/// where both reach 0.98), where slices differ; the whole axis if the curves
/// never rise there.
std::vector<std::size_t> default_slices(const std::vector<double>& verify_curve,
                                        const std::vector<double>& validate_curve, std::size_t count);

/// The axis indices nearest to `values`; an error (naming `flag`) for a value
/// outside the axis.
Result<std::vector<std::size_t>> slices_at(const std::vector<double>& axis, const std::vector<double>& values,
                                           const std::string& flag);

/// A data file's name and contents.
struct DataFile {
  std::string name;
  std::string text;
};

/// The data files, in figure order: fig09_time.dat, fig10_radius.dat,
/// fig11_joint.dat, fig12_slices_tmax.dat, fig13_slices_rmax.dat,
/// fig14_error.dat. The sides must share their grid (check_same_grid).
std::vector<DataFile> figure_data(const Side& verification, const Side& validation, const Thresholds& thresholds,
                                  const Slices& slices);

/// Writes `files` into `dir` (which must exist).
Status write_files(const std::string& dir, const std::vector<DataFile>& files);

/// A number as the data files and scripts write it: 17 significant digits,
/// enough to read back the same double.
std::string exact(double value);

}  // namespace p3at::vipars::report
