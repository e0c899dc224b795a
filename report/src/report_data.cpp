#include "p3at/report/report_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace p3at::vipars::report {
namespace {

// Thrown inside this file only, and turned into an Error at its boundary:
// reading a nested document is much clearer without a Result at every key.
struct BadDocument : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Json = nlohmann::json;

const Json& member(const Json& object, const std::string& key, const std::string& path) {
  if (!object.is_object()) throw BadDocument(path + ": expected an object");
  const auto it = object.find(key);
  if (it == object.end())
    throw BadDocument(path.empty() ? "missing key '" + key + "'" : path + ": missing key '" + key + "'");
  return *it;
}

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

double number(const Json& value, const std::string& path) {
  if (!value.is_number()) throw BadDocument(path + ": expected a number, got " + std::string(value.type_name()));
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw BadDocument(path + ": expected a finite number");
  return v;
}

double probability(const Json& value, const std::string& path) {
  const double p = number(value, path);
  if (p < 0.0 || p > 1.0) throw BadDocument(path + ": expected a probability in [0, 1], got " + value.dump());
  return p;
}

double number_at(const Json& object, const std::string& key, const std::string& path) {
  return number(member(object, key, path), join(path, key));
}

/// `key`'s array of probabilities, of exactly `size` values when given.
std::vector<double> probabilities(const Json& object, const std::string& key, const std::string& path,
                                  std::optional<std::size_t> size) {
  const std::string where = join(path, key);
  const Json& array = member(object, key, path);
  if (!array.is_array()) throw BadDocument(where + ": expected an array");
  if (size && array.size() != *size) {
    throw BadDocument(where + ": expected " + std::to_string(*size) + " values (one per axis value), got " +
                      std::to_string(array.size()));
  }
  std::vector<double> out;
  out.reserve(array.size());
  for (std::size_t i = 0; i < array.size(); ++i)
    out.push_back(probability(array[i], where + "[" + std::to_string(i) + "]"));
  return out;
}

std::vector<double> axis(const Json& grid, const std::string& key) {
  const std::string where = "grid." + key;
  const Json& array = member(grid, key, "grid");
  if (!array.is_array()) throw BadDocument(where + ": expected an array");
  if (array.size() < 2) {
    throw BadDocument(where + ": expected at least 2 values (a report plots curves; give --" + key +
                      "-range A:B:STEP)");
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < array.size(); ++i) {
    out.push_back(number(array[i], where + "[" + std::to_string(i) + "]"));
    if (i > 0 && !(out[i] > out[i - 1])) throw BadDocument(where + ": expected increasing values, got " + array.dump());
  }
  return out;
}

std::vector<std::vector<double>> matrix(const Json& grid, const std::string& key, std::size_t rows, std::size_t cols) {
  const std::string where = "grid." + key;
  const Json& array = member(grid, key, "grid");
  if (!array.is_array() || array.size() != rows) {
    throw BadDocument(where + ": expected " + std::to_string(rows) + " rows (one per tmax), got " +
                      (array.is_array() ? std::to_string(array.size()) : std::string(array.type_name())));
  }
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < rows; ++i) {
    const std::string row_path = where + "[" + std::to_string(i) + "]";
    if (!array[i].is_array() || array[i].size() != cols) {
      throw BadDocument(row_path + ": expected " + std::to_string(cols) + " numbers (one per rmax), got " +
                        (array[i].is_array() ? std::to_string(array[i].size()) : std::string(array[i].type_name())));
    }
    std::vector<double> row;
    for (std::size_t j = 0; j < cols; ++j)
      row.push_back(probability(array[i][j], row_path + "[" + std::to_string(j) + "]"));
    out.push_back(std::move(row));
  }
  return out;
}

std::optional<std::string> optional_string(const Json& doc, const std::string& key) {
  const auto it = doc.find(key);
  if (it == doc.end() || !it->is_string()) return std::nullopt;
  return it->get<std::string>();
}

/// A number under `key` if there is one (a document may predate the key).
std::optional<double> optional_number(const Json& object, const std::string& key, const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  return number(*it, join(path, key));
}

/// The document's `robots` array, if any: each robot's name and the figures both sides can give.
std::vector<RobotSide> robots(const Json& doc) {
  std::vector<RobotSide> out;
  const auto it = doc.find("robots");
  if (it == doc.end()) return out;
  if (!it->is_array()) throw BadDocument("robots: expected an array");
  for (std::size_t i = 0; i < it->size(); ++i) {
    const std::string path = "robots[" + std::to_string(i) + "]";
    const Json& robot = (*it)[i];
    RobotSide r;
    const Json& name = member(robot, "name", path);
    if (!name.is_string()) throw BadDocument(path + ".name: expected a string");
    r.name = name.get<std::string>();
    r.p_radius = optional_number(robot, "p_radius", path);
    if (r.p_radius && (*r.p_radius < 0.0 || *r.p_radius > 1.0 + 1e-9)) {
      throw BadDocument(path + ".p_radius: expected a probability in [0, 1]");
    }
    r.dist_mean_m = optional_number(robot, "dist_mean_m", path);
    r.dist_sd_m = optional_number(robot, "dist_sd_m", path);
    out.push_back(std::move(r));
  }
  return out;
}

Side read_side(const Json& doc) {
  if (!doc.is_object())
    throw BadDocument("expected a JSON object (the output of `vipars verify --json` or `vipars validate --json`)");
  Side s;
  s.mission = optional_string(doc, "mission").value_or("");
  s.tmax_s = number_at(doc, "tmax_s", "");
  s.rmax_m = number_at(doc, "rmax_m", "");
  s.threshold = number_at(doc, "threshold", "");
  s.p_time = probability(member(doc, "p_time", ""), "p_time");
  s.p_radius = probability(member(doc, "p_radius", ""), "p_radius");
  s.p_joint = probability(member(doc, "p_joint", ""), "p_joint");
  if (doc.contains("p_time_ci_low")) {
    std::vector<double> low, high;
    for (const char* key : {"p_time", "p_radius", "p_joint"}) {
      low.push_back(probability(member(doc, std::string(key) + "_ci_low", ""), std::string(key) + "_ci_low"));
      high.push_back(probability(member(doc, std::string(key) + "_ci_high", ""), std::string(key) + "_ci_high"));
    }
    s.point_ci_low = std::move(low);
    s.point_ci_high = std::move(high);
  }
  for (auto [key, target] :
       {std::pair{"runs", &s.runs}, std::pair{"failed_runs", &s.failed_runs}, std::pair{"seed", &s.seed}}) {
    if (!doc.contains(key)) continue;
    const Json& v = doc.at(key);
    if (!v.is_number_unsigned()) throw BadDocument(std::string(key) + ": expected a whole number");
    *target = v.get<std::uint64_t>();
  }
  s.decision = optional_string(doc, "decision");
  s.command = optional_string(doc, "command");
  s.mission_file = optional_string(doc, "mission_file");
  s.world_file = optional_string(doc, "world");
  s.models_file = optional_string(doc, "models_file");

  if (!doc.contains("grid")) {
    throw BadDocument("missing key 'grid': run the command with --tmax-range A:B:STEP and --rmax-range A:B:STEP");
  }
  const Json& grid = doc.at("grid");
  if (!grid.is_object()) throw BadDocument("grid: expected an object");
  s.tmax = axis(grid, "tmax");
  s.rmax = axis(grid, "rmax");
  const std::size_t nt = s.tmax.size(), nr = s.rmax.size();
  s.p_time_curve = probabilities(grid, "p_time", "grid", nt);
  s.p_radius_curve = probabilities(grid, "p_radius", "grid", nr);
  s.p_joint_grid = matrix(grid, "p_joint", nt, nr);
  if (grid.contains("region")) {
    const Json& region = grid.at("region");
    if (!region.is_array() || region.size() != nt)
      throw BadDocument("grid.region: expected " + std::to_string(nt) + " rows");
    for (std::size_t i = 0; i < nt; ++i) {
      if (!region[i].is_array() || region[i].size() != nr) {
        throw BadDocument("grid.region[" + std::to_string(i) + "]: expected " + std::to_string(nr) + " names");
      }
      std::vector<std::string> row;
      for (const Json& cell : region[i]) {
        if (!cell.is_string()) throw BadDocument("grid.region[" + std::to_string(i) + "]: expected region names");
        row.push_back(cell.get<std::string>());
      }
      s.region.push_back(std::move(row));
    }
  }
  if (grid.contains("p_time_ci_low")) {
    s.p_time_band =
        Band{probabilities(grid, "p_time_ci_low", "grid", nt), probabilities(grid, "p_time_ci_high", "grid", nt)};
    s.p_radius_band =
        Band{probabilities(grid, "p_radius_ci_low", "grid", nr), probabilities(grid, "p_radius_ci_high", "grid", nr)};
    s.p_joint_ci_low = matrix(grid, "p_joint_ci_low", nt, nr);
    s.p_joint_ci_high = matrix(grid, "p_joint_ci_high", nt, nr);
  }
  s.robots = robots(doc);
  return s;
}

/// "line:column" of a byte offset (nlohmann's parse_error::byte, 1-based).
std::string line_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  const std::size_t end = std::min(text.size(), byte > 0 ? byte - 1 : 0);
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

bool close(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); }

std::string describe_axis(const std::vector<double>& axis) {
  std::ostringstream s;
  s << axis.size() << " values " << axis.front() << ".." << axis.back();
  return s.str();
}

}  // namespace

Result<Side> side_from_json(const nlohmann::json& doc, const std::string& source) {
  try {
    Side side = read_side(doc);
    side.source = source;
    return side;
  } catch (const BadDocument& e) {
    return make_error(Error::Code::invalid_argument, source + ": " + e.what());
  } catch (const nlohmann::json::exception& e) {
    return make_error(Error::Code::invalid_argument, source + ": " + e.what());
  }
}

Result<Side> load_side(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(Error::Code::not_found, path + ": cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() repeats the position as a byte count; the line and column are what an editor needs.
    std::string what = e.what();
    const auto colon = what.rfind(": ");
    return make_error(Error::Code::invalid_argument, path + ":" + line_column(text, e.byte) + ": expected JSON (" +
                                                         (colon == std::string::npos ? what : what.substr(colon + 2)) +
                                                         ")");
  }
  return side_from_json(doc, path);
}

Status check_same_grid(const Side& v, const Side& w) {
  for (auto [name, a, b] : {std::tuple{"tmax", &v.tmax, &w.tmax}, std::tuple{"rmax", &v.rmax, &w.rmax}}) {
    bool same = a->size() == b->size();
    for (std::size_t i = 0; same && i < a->size(); ++i) same = close((*a)[i], (*b)[i]);
    if (!same) {
      return make_error(Error::Code::invalid_argument,
                        std::string("the grids differ: ") + name + " has " + describe_axis(*a) + " in " + v.source +
                            " but " + describe_axis(*b) + " in " + w.source +
                            "; run verify and validate with the same --" + name + "-range");
    }
  }
  return {};
}

Status check_roles(const Side& v, const Side& w) {
  if (v.runs || v.p_time_band) {
    return make_error(Error::Code::invalid_argument,
                      v.source +
                          ": expected the output of `vipars verify --json`, but it has the validation's 'runs' "
                          "and confidence intervals (are --verify and --validate swapped?)");
  }
  if (!w.runs || !w.p_time_band || !w.point_ci_low) {
    return make_error(Error::Code::invalid_argument,
                      w.source +
                          ": expected the output of `vipars validate --json`, with 'runs' and the grid's "
                          "confidence intervals (grid.p_time_ci_low, ...)");
  }
  return {};
}

}  // namespace p3at::vipars::report
