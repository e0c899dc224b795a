// write_calibration_log(): the log back as CSV, every number as the shortest
// decimal that reads back as the same double, so a log written by
// `vipars calibrate --log-out` and fitted again with --from-log gives exactly
// the same models file.

#include <array>
#include <charconv>
#include <optional>
#include <string>
#include <system_error>

#include "p3at/common/number_format.hpp"
#include "p3at/verifier/calibration.hpp"

namespace p3at::verifier {
namespace {

std::string optional_number(const std::optional<double>& value) { return value ? format_shortest(*value) : std::string(); }

}  // namespace

std::string write_calibration_log(const CalibrationLog& log) {
  std::string out;
  for (const std::string& c : calibration_log_columns()) out += (out.empty() ? "" : ",") + c;
  out += "\n";
  for (const Manoeuvre& m : log.manoeuvres) {
    const std::string head = m.robot + "," + std::to_string(m.id) + "," + to_string(m.kind) + ",";
    for (const CycleRow& r : m.rows) {
      out += head + format_shortest(r.t_s) + "," + format_shortest(r.cmd_trans_mps) + "," + format_shortest(r.cmd_rot_radps) + "," +
             format_shortest(r.odom_x_m) + "," + format_shortest(r.odom_y_m) + "," + format_shortest(r.odom_theta_rad) + ",";
      if (r.truth) {
        out += format_shortest(r.truth->x_m) + "," + format_shortest(r.truth->y_m) + "," + format_shortest(r.truth->theta_rad);
      } else {
        out += ",,";
      }
      out += ",,,\n";
    }
  }
  for (const MessageRow& m : log.messages) {
    out += m.sender + "," + std::to_string(m.id) + ",message,,,,,,,,,," + format_shortest(m.sent_s) + "," +
           optional_number(m.delivered_s) + "," + optional_number(m.acked_s) + "\n";
  }
  return out;
}

}  // namespace p3at::verifier
