#include "p3at/report/command_lines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <utility>

namespace p3at::vipars::report {
namespace {

std::string number(double value, int digits = 15) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

void add_criterion_and_grid(std::vector<std::string>& words, const Side& s) {
  words.insert(words.end(), {"--tmax", number(s.tmax_s), "--rmax", number(s.rmax_m)});
  for (auto [flag, axis] : {std::pair{"--tmax-range", &s.tmax}, std::pair{"--rmax-range", &s.rmax}}) {
    const auto range = range_text(*axis);
    words.insert(words.end(), {flag, range.value_or("UNEVEN-AXIS")});
  }
  words.push_back("--json");
}

}  // namespace

std::string shell_quote(const std::string& word) {
  if (word.empty()) return "''";
  bool safe = true;
  for (const char c : word) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    std::string_view("_-./:=,+@%").find(c) != std::string_view::npos;
    safe = safe && ok;
  }
  if (safe) return word;
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string shell_join(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + shell_quote(w);
  return out;
}

std::optional<std::string> range_text(const std::vector<double>& axis) {
  if (axis.size() < 2) return std::nullopt;
  const double a = axis.front(), b = axis.back();
  const double step = (b - a) / static_cast<double>(axis.size() - 1);
  // The axis came from A + k·STEP rounded to 15 digits (range_arg.hpp): allow that rounding.
  for (std::size_t k = 0; k < axis.size(); ++k) {
    if (std::abs(axis[k] - (a + static_cast<double>(k) * step)) > 1e-9 * std::max(1.0, std::abs(axis[k])))
      return std::nullopt;
  }
  return number(a) + ":" + number(b) + ":" + number(step, 12);
}

std::string verify_command(const Side& v, const std::string& mission_file, const std::string& models_file,
                           const std::string& output) {
  std::vector<std::string> words{"vipars", "verify", mission_file.empty() ? "MISSION.yaml" : mission_file, "--models",
                                 models_file.empty() ? "MODELS.yaml" : models_file};
  add_criterion_and_grid(words, v);
  return shell_join(words) + " > " + shell_quote(output);
}

std::string validate_command(const Side& w, const std::string& output) {
  std::vector<std::string> words{"vipars", "validate", w.mission_file.value_or("MISSION.yaml"), "--world",
                                 w.world_file.value_or("WORLD.yaml")};
  if (w.runs) words.insert(words.end(), {"--trials", std::to_string(*w.runs)});
  if (w.seed) words.insert(words.end(), {"--seed", std::to_string(*w.seed)});
  add_criterion_and_grid(words, w);
  return shell_join(words) + " > " + shell_quote(output);
}

}  // namespace p3at::vipars::report
