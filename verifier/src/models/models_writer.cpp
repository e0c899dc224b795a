// write_models(): Models back into the documented file format. Each value is
// printed in the file's units as the shortest decimal that the loader turns
// back into the same double when one exists near the converted value (for the
// plain ones always), so a calibrated file reloads to what calibration found.

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include "models/units.hpp"
#include "models/yaml_access.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::verifier {
namespace {

using p3at::format_shortest;

// How many doubles either side of the converted value are tried.
constexpr int kNeighbours = 8;

void require_finite(double value, std::string_view what) {
  if (!std::isfinite(value)) throw std::invalid_argument("write_models: " + std::string(what) + " is not finite");
}

// `si` in the file's unit: to_file(si), or a neighbour of it that from_file
// maps back to exactly `si`.
template <typename ToFile, typename FromFile>
std::string in_file_units(double si, std::string_view what, ToFile to_file, FromFile from_file) {
  require_finite(si, what);
  const double guess = to_file(si);
  if (from_file(guess) == si) return format_shortest(guess);
  double up = guess;
  double down = guess;
  for (int i = 0; i < kNeighbours; ++i) {
    up = std::nextafter(up, HUGE_VAL);
    down = std::nextafter(down, -HUGE_VAL);
    if (from_file(up) == si) return format_shortest(up);
    if (from_file(down) == si) return format_shortest(down);
  }
  return format_shortest(guess);
}

std::string plain(double value, std::string_view what) {
  require_finite(value, what);
  return format_shortest(value);
}
std::string degrees(double radians, std::string_view what) {
  return in_file_units(radians, what, models_detail::radians_to_degrees, models_detail::degrees_to_radians);
}
std::string sd_of_var(double var, std::string_view what) {
  if (var < 0.0) throw std::invalid_argument("write_models: " + std::string(what) + " is negative");
  return in_file_units(var, what, [](double v) { return std::sqrt(v); }, models_detail::sd_to_var);
}
std::string ms(double seconds, std::string_view what) {
  return in_file_units(seconds, what, models_detail::s_to_ms, models_detail::ms_to_s);
}
std::string sd_ms_of_var_s(double var, std::string_view what) {
  if (var < 0.0) throw std::invalid_argument("write_models: " + std::string(what) + " is negative");
  return in_file_units(var, what, [](double v) { return models_detail::s_to_ms(std::sqrt(v)); },
                       models_detail::sd_ms_to_var_s);
}

// A YAML double-quoted string: any text survives the round trip.
std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      constexpr std::string_view kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4U];
      out += kHex[byte & 0xFU];
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A name plain when YAML reads it back as that same string, quoted otherwise.
std::string name_text(std::string_view name) {
  bool simple = !name.empty() && !(name.front() >= '0' && name.front() <= '9');
  for (char c : name) {
    simple = simple && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_');
  }
  // Words YAML resolves to null or a boolean (in any of their spellings).
  for (std::string_view word : {"null", "Null", "NULL", "true", "True", "TRUE", "false", "False", "FALSE", "y", "Y",
                                "yes", "Yes", "YES", "n", "N", "no", "No", "NO", "on", "On", "ON", "off", "Off", "OFF"}) {
    simple = simple && name != word;
  }
  return simple ? std::string(name) : quoted(name);
}

void write_delay(std::string& out, std::string_view key, const Mixture1& mixture) {
  if (mixture.components.empty()) return;  // absent: the loader's default (a point mass at 0)
  out += "  " + std::string(key) + ":\n";
  for (const Component1& c : mixture.components) {
    out += "    - {weight: " + plain(c.weight, "a delay component's weight") +
           ", mean: " + ms(c.mean, "a delay component's mean") +
           ", sd: " + sd_ms_of_var_s(c.var, "a delay component's variance") + "}\n";
  }
}

}  // namespace

std::string write_models(const Models& models) {
  std::string out;
  out += "# Robot models for the VIPARS verifier: what it knows of each robot's motion,\n";
  out += "# the team link and the environment (docs/robot-models.md). Units are in the\n";
  out += "# key names; standard deviations are per square root of the distance or angle.\n";
  out += "models:\n";
  out += "  version: 1\n";
  if (!models.generated_by.empty()) out += "  generated_by: " + quoted(models.generated_by) + "\n";

  out += "robots:\n";
  for (const RobotModel& r : models.robots) {
    const Kinematics& k = r.kinematics;
    const MotionError& e = r.motion;
    out += "  - name: " + name_text(r.name) + "\n";
    out += "    kinematics:\n";
    out += "      cycle_s: " + plain(k.cycle_s, "cycle_s") + "\n";
    out += "      max_rot_vel_degps: " + degrees(k.max_rot_vel_radps, "max_rot_vel_radps") + "\n";
    out += "      trans_accel_mps2: " + plain(k.trans_accel_mps2, "trans_accel_mps2") + "\n";
    out += "      trans_decel_mps2: " + plain(k.trans_decel_mps2, "trans_decel_mps2") + "\n";
    out += "      rot_accel_degps2: " + degrees(k.rot_accel_radps2, "rot_accel_radps2") + "\n";
    out += "      rot_decel_degps2: " + degrees(k.rot_decel_radps2, "rot_decel_radps2") + "\n";
    out += "      robot_radius_m: " + plain(k.robot_radius_m, "robot_radius_m") + "\n";
    out += "      rot_gain: " + plain(k.rot_gain, "rot_gain") + "\n";
    if (k.calibrated_speed_mps > 0.0) {
      out += "      calibrated_speed_mps: " + plain(k.calibrated_speed_mps, "calibrated_speed_mps") + "\n";
    }
    out += "      top_speed_mps: " + plain(k.top_speed_mps, "top_speed_mps") + "\n";
    out += "    motion:\n";
    out += "      trans_scale: " + plain(e.trans_scale, "trans_scale") + "\n";
    out += "      rot_scale: " + plain(e.rot_scale, "rot_scale") + "\n";
    out += "      drift_deg_per_m: " + degrees(e.drift_rad_per_m, "drift_rad_per_m") + "\n";
    if (e.trans_per_rad_m != 0.0) out += "      trans_per_rad_m: " + plain(e.trans_per_rad_m, "trans_per_rad_m") + "\n";
    out += "      trans_sd_per_sqrt_m: " + sd_of_var(e.trans_var_per_m, "trans_var_per_m") + "\n";
    out += "      rot_sd_per_sqrt_rad: " + sd_of_var(e.rot_var_per_rad, "rot_var_per_rad") + "\n";
    out += "      heading_sd_per_sqrt_m: " + sd_of_var(e.heading_var_per_m, "heading_var_per_m") + "\n";
    out += "      trans_rel_sd: " + sd_of_var(e.trans_rel_var, "trans_rel_var") + "\n";
    out += "      rot_rel_sd: " + sd_of_var(e.rot_rel_var, "rot_rel_var") + "\n";
  }

  if (!models.comm.delivery_s.components.empty() || !models.comm.ack_s.components.empty()) {
    out += "communication:\n";
    write_delay(out, "delivery_ms", models.comm.delivery_s);
    write_delay(out, "ack_ms", models.comm.ack_s);
  }

  const Environment& env = models.environment;
  out += "environment:\n";
  out += "  sonar_max_range_m: " + plain(env.sonar_max_range_m, "sonar_max_range_m") + "\n";
  if (!env.walls.empty()) {
    out += "  walls:                         # [x0, y0, x1, y1], metres\n";
    for (const Wall& w : env.walls) {
      out += "    - [" + plain(w.x0_m, "a wall") + ", " + plain(w.y0_m, "a wall") + ", " + plain(w.x1_m, "a wall") +
             ", " + plain(w.y1_m, "a wall") + "]\n";
    }
  }

  const Budget& b = models.budget;
  out += "budget:\n";
  out += "  max_components: " + std::to_string(b.max_components) + "\n";
  out += "  max_branches: " + std::to_string(b.max_branches) + "\n";
  out += "  noise_sigma_points: " + std::to_string(b.noise_sigma_points) + "\n";
  out += "  max_events: " + std::to_string(b.max_events) + "\n";
  out += "  max_work_cycles: " + std::to_string(b.max_work_cycles) + "\n";
  return out;
}

}  // namespace p3at::verifier
