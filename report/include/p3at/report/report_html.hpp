#pragma once
// The report's one-page summary, index.html: the verdict against the error
// bounds, the numbers at the criterion point, the errors and where they
// occur, the figures, the SHA-256 of every input file and the commands that
// made the report, so a reader can check what it was made from and redo it.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/report/report_data.hpp"
#include "p3at/report/report_errors.hpp"
#include "p3at/report/report_plots.hpp"

namespace p3at::vipars::report {

/// SHA-256 of bytes / of a file's contents, as 64 lowercase hex digits (libsodium).
std::string sha256_hex(std::string_view bytes);
Result<std::string> sha256_file(const std::string& path);

struct InputFile {
  std::string role;  ///< "verification (--verify)", "world", ...
  std::string path;
  std::uintmax_t bytes = 0;
  std::string sha256;
};
/// The file's size and hash; an error when it cannot be read.
Result<InputFile> describe_input(const std::string& role, const std::string& path);

struct HtmlInputs {
  const Side& verification;
  const Side& validation;
  Thresholds thresholds;
  Comparison comparison;
  std::string title;
  std::vector<InputFile> inputs;
  std::vector<std::pair<std::string, std::string>> commands;  ///< what it is, the command line
  std::vector<FigureScript> figures;
  bool figures_rendered = true;    ///< false with --no-plots: the page links the scripts instead
  std::vector<std::string> notes;  ///< extra lines (timings of a run made by the report itself)
};

std::string report_html(const HtmlInputs& inputs);

/// Text safe inside HTML elements and attribute values.
std::string html_escape(std::string_view text);

}  // namespace p3at::vipars::report
