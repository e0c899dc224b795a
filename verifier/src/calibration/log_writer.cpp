// write_calibration_log(): the log back as CSV, every number as the shortest
// decimal that reads back as the same double, so a log written by
// `vipars calibrate --log-out` and fitted again with --from-log gives exactly
// the same models file.

#include <array>
#include <charconv>
#include <optional>
#include <string>
#include <system_error>

#include "p3at/verifier/calibration.hpp"

namespace p3at::verifier {
namespace {

std::string number(double value) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (ec != std::errc()) return "nan";  // not reachable for a double in 32 characters
  return std::string(buffer.data(), end);
}

std::string optional_number(const std::optional<double>& value) { return value ? number(*value) : std::string(); }

}  // namespace

std::string write_calibration_log(const CalibrationLog& log) {
  std::string out;
  for (const std::string& c : calibration_log_columns()) out += (out.empty() ? "" : ",") + c;
  out += "\n";
  for (const Manoeuvre& m : log.manoeuvres) {
    const std::string head = m.robot + "," + std::to_string(m.id) + "," + to_string(m.kind) + ",";
    for (const CycleRow& r : m.rows) {
      out += head + number(r.t_s) + "," + number(r.cmd_trans_mps) + "," + number(r.cmd_rot_radps) + "," +
             number(r.odom_x_m) + "," + number(r.odom_y_m) + "," + number(r.odom_theta_rad) + ",";
      if (r.truth) {
        out += number(r.truth->x_m) + "," + number(r.truth->y_m) + "," + number(r.truth->theta_rad);
      } else {
        out += ",,";
      }
      out += ",,,\n";
    }
  }
  for (const MessageRow& m : log.messages) {
    out += m.sender + "," + std::to_string(m.id) + ",message,,,,,,,,,," + number(m.sent_s) + "," +
           optional_number(m.delivered_s) + "," + optional_number(m.acked_s) + "\n";
  }
  return out;
}

}  // namespace p3at::verifier
