#pragma once
/// The one error type of every reader of input files (missions, robot models,
/// worlds, criterion files, PARS programs, calibration logs): what was wrong
/// and where. what() is the whole one-line message, "file:line:column: detail",
/// or "file: detail" when there is no position. Each reader throws its own
/// subclass (MissionError, ModelsError, ...) so that a caller can tell which
/// input was bad; the subclasses add nothing.

#include <stdexcept>
#include <string>
#include <utility>

namespace p3at {

class LocatedError : public std::runtime_error {
 public:
  LocatedError(std::string file, int line, int column, std::string detail)
      : std::runtime_error(format(file, line, column, detail)),
        file_(std::move(file)),
        line_(line),
        column_(column),
        detail_(std::move(detail)) {}

  /// The file (or other source name) the input came from.
  const std::string& file() const { return file_; }
  /// 1-based line of the offending input; 0 if the error has no position.
  int line() const { return line_; }
  /// 1-based column of the offending input; 0 if the error has no position.
  int column() const { return column_; }
  /// The message without the location prefix.
  const std::string& detail() const { return detail_; }

  /// "file:line:column: detail", or "file: detail" when line <= 0.
  static std::string format(const std::string& file, int line, int column, const std::string& detail) {
    if (line <= 0) return file + ": " + detail;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + detail;
  }

 private:
  std::string file_;
  int line_ = 0;
  int column_ = 0;
  std::string detail_;
};

}  // namespace p3at
