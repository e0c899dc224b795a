#pragma once
// The report's figures: one gnuplot script per figure (the seed paper's
// Figs. 9–13 and the error map), each plotting only its .dat file
// (report_dat.hpp) and writing a PNG (pngcairo) and an SVG. The scripts use
// relative names, so `gnuplot fig09_time.gp` in the report's folder redraws a
// figure after editing it.

#include <string>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/report/report_dat.hpp"
#include "p3at/report/report_data.hpp"
#include "p3at/report/report_errors.hpp"

namespace p3at::vipars::report {

/// What the figures are drawn from.
struct PlotInputs {
  const Side& verification;
  const Side& validation;
  Thresholds thresholds;
  Comparison comparison;
  Slices slices;
  std::string title;  ///< prefix of every figure's title (default: the mission's name)
};

struct FigureScript {
  std::string stem;     ///< "fig09_time": the script is stem.gp, the figures stem.png and stem.svg
  std::string caption;  ///< one sentence for the HTML page
  std::string text;     ///< the gnuplot script
};

/// The six scripts, in figure order (the same order as figure_data()).
std::vector<FigureScript> figure_scripts(const PlotInputs& inputs);

/// Runs `gnuplot` (a name looked up in PATH, or a path) on stem.gp inside
/// `dir`, and checks that stem.png and stem.svg came out non-empty. Returns
/// what gnuplot printed (warnings), or an error with it when gnuplot failed or
/// could not be started.
Result<std::string> render(const std::string& gnuplot, const std::string& dir, const FigureScript& script);

/// A string as a gnuplot double-quoted literal (quotes and backslashes escaped).
std::string gnuplot_quote(const std::string& text);

}  // namespace p3at::vipars::report
