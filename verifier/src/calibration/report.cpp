// format_calibration_report(): how well each parameter is known, one line
// each, in the models file's units, so the report and the file read alike.

#include <cmath>
#include <cstdio>
#include <string>

#include "p3at/common/number_format.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::verifier {
namespace {

// At least one space after the text, more to reach `width`.
std::string padded(std::string text, std::size_t width) {
  text.append(text.size() < width ? width - text.size() : 1, ' ');
  return text;
}

std::string with_unit(double v, const std::string& unit) {
  return unit.empty() ? format_general(v) : format_general(v) + " " + unit;
}

void delay_lines(std::string& out, const char* name, const DelayCalibration& d) {
  out += std::string(name) + ": " + std::to_string(d.samples) + " messages";
  if (d.lost > 0) out += " (" + std::to_string(d.lost) + " more never arrived: not in the mixture)";
  if (d.mixture.components.empty()) {
    out += ", no fit\n";
    return;
  }
  out += ", " + std::to_string(d.mixture.components.size()) + " component(s) chosen by BIC";
  if (!d.bic.empty()) {
    out += " (BIC for 1..";
    out += std::to_string(d.bic.size()) + ":";
    for (double b : d.bic) out += " " + format_general(b);
    out += ")";
  }
  out += ", KS distance " + format_general(d.ks_distance) + "\n";
  for (const Component1& c : d.mixture.components) {
    out += "  weight " + padded(format_general(c.weight), 10) + " mean " + padded(format_general(c.mean * 1e3) + " ms", 14) + " sd " +
           format_general(std::sqrt(c.var) * 1e3) + " ms\n";
  }
  out += "  overall: mean " + format_general(d.mixture.mean() * 1e3) + " ms, sd " + format_general(std::sqrt(d.mixture.variance()) * 1e3) +
         " ms\n";
}

}  // namespace

std::string format_calibration_report(const CalibrationResult& result) {
  std::string out;
  for (const RobotCalibration& r : result.robots) {
    out += r.model.name + ": " + std::to_string(r.straights) + " straight runs and " + std::to_string(r.spins) +
           " spins with true poses\n";
    out += "  " + padded("parameter", 22) + padded("value", 26) + padded("std.error", 12) +
           padded("resid.rms", 18) + padded("runs", 6) + "note\n";
    for (const ParameterFit& f : r.fits) {
      out += "  " + padded(f.name, 22) + padded(with_unit(f.value, f.unit), 26) +
             padded(f.std_error >= 0.0 ? format_general(f.std_error) : "-", 12) +
             padded(f.residual_rms >= 0.0 ? with_unit(f.residual_rms, f.residual_unit) : "-", 18) +
             padded(f.runs > 0 ? std::to_string(f.runs) : "-", 6) + f.note + "\n";
    }
  }
  delay_lines(out, "delivery_ms", result.delivery);
  delay_lines(out, "ack_ms", result.ack);
  for (const std::string& w : result.warnings) out += "warning: " + w + "\n";
  return out;
}

}  // namespace p3at::verifier
