#include "p3at/report/report_errors.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace p3at::vipars::report {
namespace {

// Accumulates one point at a time, so the curves and the surface share one rule
// for ties (the first maximum in axis order wins) and for the region breakdown.
class Accumulator {
 public:
  Accumulator(const Thresholds& thresholds, double limit) : thresholds_(thresholds) { summary_.limit = limit; }

  void add(double verify, double validate, std::optional<double> tmax_s, std::optional<double> rmax_m,
           std::optional<double> ci_low, std::optional<double> ci_high) {
    const double error = std::abs(verify - validate);
    if (summary_.points == 0 || error > summary_.max) {
      summary_.max = error;
      summary_.at_tmax_s = tmax_s;
      summary_.at_rmax_m = rmax_m;
      summary_.verify = verify;
      summary_.validate = validate;
    }
    ++summary_.points;
    sum_ += error;
    if (ci_low && ci_high && verify >= *ci_low && verify <= *ci_high) ++summary_.within_ci;
    auto& by_region = summary_.max_by_region[static_cast<std::size_t>(classify(verify, thresholds_))];
    by_region = std::max(by_region.value_or(0.0), error);
  }

  ErrorSummary done() {
    summary_.mean = summary_.points > 0 ? sum_ / static_cast<double>(summary_.points) : 0.0;
    return summary_;
  }

 private:
  Thresholds thresholds_;
  ErrorSummary summary_;
  double sum_ = 0.0;
};

std::optional<double> at(const std::optional<Band>& band, bool low, std::size_t i) {
  if (!band) return std::nullopt;
  return low ? band->low[i] : band->high[i];
}

nlohmann::ordered_json summary_json(const ErrorSummary& s) {
  nlohmann::ordered_json j;
  j["max_abs_error"] = s.max;
  if (s.at_tmax_s) j["at_tmax_s"] = *s.at_tmax_s;
  if (s.at_rmax_m) j["at_rmax_m"] = *s.at_rmax_m;
  j["verify"] = s.verify;
  j["validate"] = s.validate;
  j["limit"] = s.limit;
  j["pass"] = s.pass();
  j["mean_abs_error"] = s.mean;
  j["points"] = s.points;
  j["verify_within_validation_ci"] = s.within_ci;
  nlohmann::ordered_json regions = nlohmann::ordered_json::object();
  for (Region r : {Region::unsuccessful, Region::uncertain, Region::successful}) {
    const auto& value = s.max_by_region[static_cast<std::size_t>(r)];
    regions[to_string(r)] = value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
  }
  j["max_abs_error_by_region"] = regions;
  return j;
}

}  // namespace

Region classify(double p, const Thresholds& t) {
  if (p < t.low) return Region::unsuccessful;
  if (p >= t.high) return Region::successful;
  return Region::uncertain;
}

const char* to_string(Region region) {
  switch (region) {
    case Region::unsuccessful:
      return "unsuccessful";
    case Region::uncertain:
      return "uncertain";
    case Region::successful:
      return "successful";
  }
  return "?";
}

Comparison compare(const Side& v, const Side& w, const Thresholds& thresholds, const Limits& limits) {
  Accumulator time(thresholds, limits.time), radius(thresholds, limits.radius), joint(thresholds, limits.joint);
  for (std::size_t i = 0; i < v.tmax.size(); ++i) {
    time.add(v.p_time_curve[i], w.p_time_curve[i], v.tmax[i], std::nullopt, at(w.p_time_band, true, i),
             at(w.p_time_band, false, i));
  }
  for (std::size_t j = 0; j < v.rmax.size(); ++j) {
    radius.add(v.p_radius_curve[j], w.p_radius_curve[j], std::nullopt, v.rmax[j], at(w.p_radius_band, true, j),
               at(w.p_radius_band, false, j));
  }
  for (std::size_t i = 0; i < v.tmax.size(); ++i) {
    for (std::size_t j = 0; j < v.rmax.size(); ++j) {
      std::optional<double> low, high;
      if (w.p_joint_ci_low && w.p_joint_ci_high) {
        low = (*w.p_joint_ci_low)[i][j];
        high = (*w.p_joint_ci_high)[i][j];
      }
      joint.add(v.p_joint_grid[i][j], w.p_joint_grid[i][j], v.tmax[i], v.rmax[j], low, high);
    }
  }
  return Comparison{time.done(), radius.done(), joint.done()};
}

nlohmann::ordered_json errors_json(const Comparison& c, const Thresholds& thresholds) {
  nlohmann::ordered_json j;
  j["time"] = summary_json(c.time);
  j["radius"] = summary_json(c.radius);
  j["joint"] = summary_json(c.joint);
  j["region_low"] = thresholds.low;
  j["region_high"] = thresholds.high;
  j["pass"] = c.pass();
  return j;
}

}  // namespace p3at::vipars::report
