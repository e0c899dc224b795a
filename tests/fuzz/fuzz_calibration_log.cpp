// libFuzzer target for the calibration log reader (docs/calibration.md: the
// CSV a lab writes from its own runs): any input either parses or throws
// CalibrationLogError naming a line and saying what was expected (never
// anything else, never a crash), and whatever parses is written back by
// write_calibration_log() to CSV that parses to the same log.
// Seeds: tests/fuzz/corpus/calibration (cut from a `vipars calibrate --log-out` file).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "p3at/verifier/calibration.hpp"

namespace {

bool parses(std::string_view text, p3at::verifier::CalibrationLog& log) {
  try {
    log = p3at::verifier::parse_calibration_log(text, "fuzz.csv");
    return true;
  } catch (const p3at::verifier::CalibrationLogError& e) {
    // Every rejection says where and what was wrong.
    if (e.detail().empty() || e.line() < 1 || e.file() != "fuzz.csv") std::abort();
    return false;
  }
}

// The log's content without where each row came from (CycleRow::line,
// MessageRow::line): writing renumbers the lines.
p3at::verifier::CalibrationLog content(p3at::verifier::CalibrationLog log) {
  for (auto& m : log.manoeuvres) {
    for (auto& row : m.rows) row.line = 0;
  }
  for (auto& message : log.messages) message.line = 0;
  return log;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  p3at::verifier::CalibrationLog log;
  if (!parses(text, log)) return 0;
  const std::string written = p3at::verifier::write_calibration_log(log);
  p3at::verifier::CalibrationLog again;
  if (!parses(written, again)) std::abort();  // what we write must read back
  if (!(content(again) == content(log))) std::abort();  // ... to the same log (numbers round-trip exactly)
  return 0;
}
