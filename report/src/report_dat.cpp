#include "p3at/report/report_dat.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace p3at::vipars::report {
namespace {

// Missing intervals (a validation document without them never gets this far,
// check_roles) would be written as gnuplot's missing-value marker.
std::string maybe(const std::optional<Band>& band, bool low, std::size_t i) {
  if (!band) return "NaN";
  return exact(low ? band->low[i] : band->high[i]);
}

std::string joint_ci(const Side& w, bool low, std::size_t i, std::size_t j) {
  const auto& m = low ? w.p_joint_ci_low : w.p_joint_ci_high;
  return m ? exact((*m)[i][j]) : "NaN";
}

std::string curve_file(const std::string& axis_column, const std::vector<double>& axis, const std::vector<double>& v,
                       const std::vector<double>& w, const std::optional<Band>& band, const Thresholds& t) {
  std::string s = "# " + axis_column +
                  " p_verify p_validate ci_low ci_high abs_error region\n"
                  "# region by p_verify: 0 unsuccessful (< " +
                  exact(t.low) + "), 1 uncertain, 2 successful (>= " + exact(t.high) + ")\n";
  for (std::size_t i = 0; i < axis.size(); ++i) {
    s += exact(axis[i]) + " " + exact(v[i]) + " " + exact(w[i]) + " " + maybe(band, true, i) + " " +
         maybe(band, false, i) + " " + exact(std::abs(v[i] - w[i])) + " " +
         std::to_string(static_cast<int>(classify(v[i], t))) + "\n";
  }
  return s;
}

}  // namespace

std::string exact(double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

std::vector<std::size_t> default_slices(const std::vector<double>& v, const std::vector<double>& w, std::size_t count) {
  const std::size_t n = std::min(v.size(), w.size());
  if (n == 0 || count == 0) return {};
  std::size_t lo = 0, hi = n - 1;
  while (lo < n && std::max(v[lo], w[lo]) < 0.02) ++lo;
  std::size_t top = lo;
  while (top < n && std::min(v[top], w[top]) < 0.98) ++top;
  if (lo < n) hi = std::min(top, n - 1);
  if (lo >= hi) {
    lo = 0;
    hi = n - 1;
  }
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < count; ++k) {
    const double f = count == 1 ? 0.5 : static_cast<double>(k) / static_cast<double>(count - 1);
    const auto idx = lo + static_cast<std::size_t>(std::lround(f * static_cast<double>(hi - lo)));
    if (out.empty() || out.back() != idx) out.push_back(idx);
  }
  return out;
}

Result<std::vector<std::size_t>> slices_at(const std::vector<double>& axis, const std::vector<double>& values,
                                           const std::string& flag) {
  std::vector<std::size_t> out;
  for (const double value : values) {
    const double step = axis.size() > 1 ? (axis.back() - axis.front()) / static_cast<double>(axis.size() - 1) : 0.0;
    if (!(value >= axis.front() - step / 2 && value <= axis.back() + step / 2)) {
      return make_error(Error::Code::invalid_argument, flag + ": " + exact(value) + " is outside the grid's axis " +
                                                           exact(axis.front()) + ".." + exact(axis.back()));
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i < axis.size(); ++i) {
      if (std::abs(axis[i] - value) < std::abs(axis[best] - value)) best = i;
    }
    if (std::find(out.begin(), out.end(), best) == out.end()) out.push_back(best);
  }
  return out;
}

std::vector<DataFile> figure_data(const Side& v, const Side& w, const Thresholds& t, const Slices& slices) {
  std::vector<DataFile> files;
  files.push_back({"fig09_time.dat", curve_file("tmax_s", v.tmax, v.p_time_curve, w.p_time_curve, w.p_time_band, t)});
  files.push_back(
      {"fig10_radius.dat", curve_file("rmax_m", v.rmax, v.p_radius_curve, w.p_radius_curve, w.p_radius_band, t)});

  // The surface: one block per tmax (gnuplot's grid format for pm3d and image).
  std::string joint = "# tmax_s rmax_m p_verify p_validate ci_low ci_high abs_error; one block per tmax\n";
  std::string error = "# tmax_s rmax_m abs_error; one block per tmax\n";
  for (std::size_t i = 0; i < v.tmax.size(); ++i) {
    for (std::size_t j = 0; j < v.rmax.size(); ++j) {
      const double pv = v.p_joint_grid[i][j], pw = w.p_joint_grid[i][j];
      const std::string cell = exact(v.tmax[i]) + " " + exact(v.rmax[j]);
      joint += cell + " " + exact(pv) + " " + exact(pw) + " " + joint_ci(w, true, i, j) + " " +
               joint_ci(w, false, i, j) + " " + exact(std::abs(pv - pw)) + "\n";
      error += cell + " " + exact(std::abs(pv - pw)) + "\n";
    }
    joint += "\n";
    error += "\n";
  }
  files.push_back({"fig11_joint.dat", std::move(joint)});

  // Slices: one gnuplot data set (index) per slice, separated by two blank lines.
  std::string by_tmax = "# tmax_s p_verify p_validate ci_low ci_high; one data set (index) per rmax slice\n";
  for (const std::size_t j : slices.rmax) {
    by_tmax += "# rmax_m " + exact(v.rmax[j]) + "\n";
    for (std::size_t i = 0; i < v.tmax.size(); ++i) {
      by_tmax += exact(v.tmax[i]) + " " + exact(v.p_joint_grid[i][j]) + " " + exact(w.p_joint_grid[i][j]) + " " +
                 joint_ci(w, true, i, j) + " " + joint_ci(w, false, i, j) + "\n";
    }
    by_tmax += "\n\n";
  }
  files.push_back({"fig12_slices_tmax.dat", std::move(by_tmax)});
  std::string by_rmax = "# rmax_m p_verify p_validate ci_low ci_high; one data set (index) per tmax slice\n";
  for (const std::size_t i : slices.tmax) {
    by_rmax += "# tmax_s " + exact(v.tmax[i]) + "\n";
    for (std::size_t j = 0; j < v.rmax.size(); ++j) {
      by_rmax += exact(v.rmax[j]) + " " + exact(v.p_joint_grid[i][j]) + " " + exact(w.p_joint_grid[i][j]) + " " +
                 joint_ci(w, true, i, j) + " " + joint_ci(w, false, i, j) + "\n";
    }
    by_rmax += "\n\n";
  }
  files.push_back({"fig13_slices_rmax.dat", std::move(by_rmax)});
  files.push_back({"fig14_error.dat", std::move(error)});
  return files;
}

Status write_files(const std::string& dir, const std::vector<DataFile>& files) {
  for (const DataFile& f : files) {
    const std::string path = dir + "/" + f.name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << f.text;
    out.close();
    if (!out) return make_error(Error::Code::io, path + ": cannot write");
  }
  return {};
}

}  // namespace p3at::vipars::report
