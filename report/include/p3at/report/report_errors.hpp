#pragma once
// The verification error (the seed paper's section VI.C: "the difference
// between verification and validation"): |verify − validate| over the P(t ≤ Tmax)
// curve, the P(every r ≤ Rmax) curve and the joint surface, its maximum and
// where it occurs, judged against issue #5's bounds (0.05, 0.05, 0.08), and
// broken down by the paper's three regions.

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>

#include "p3at/report/report_data.hpp"

namespace p3at::vipars::report {

/// The paper's three regions, by the verification's probability: below `low`
/// high-confidence unsuccessful, at or above `high` high-confidence
/// successful, else uncertain (the same rule as `vipars verify`'s grid).
enum class Region { unsuccessful = 0, uncertain = 1, successful = 2 };
struct Thresholds {
  double low = 0.05;
  double high = 0.95;
};
Region classify(double p, const Thresholds& thresholds);
const char* to_string(Region region);  ///< "unsuccessful", "uncertain", "successful"

/// The largest |verify − validate| a report may show (issue #5).
struct Limits {
  double time = 0.05;    ///< over the P(t ≤ Tmax) curve
  double radius = 0.05;  ///< over the P(every r ≤ Rmax) curve
  double joint = 0.08;   ///< over the joint surface
};

/// |verify − validate| over one curve or the surface.
struct ErrorSummary {
  double max = 0.0;                 ///< the largest |verify − validate|
  std::optional<double> at_tmax_s;  ///< where (the first such point in axis order)
  std::optional<double> at_rmax_m;
  double verify = 0.0, validate = 0.0;  ///< the two values there
  double mean = 0.0;                    ///< mean |verify − validate| over the points
  std::size_t points = 0;
  std::size_t within_ci = 0;  ///< points where verify lies inside the validation's 95 % interval
  std::array<std::optional<double>, 3> max_by_region;  ///< indexed by Region; none when no point is in it
  double limit = 0.0;
  bool pass() const { return max <= limit; }
};

struct Comparison {
  ErrorSummary time, radius, joint;
  bool pass() const { return time.pass() && radius.pass() && joint.pass(); }
};

/// Compares two sides on the same grid (check_same_grid first). The
/// validation's intervals, when present, give `within_ci`.
Comparison compare(const Side& verification, const Side& validation, const Thresholds& thresholds = {},
                   const Limits& limits = {});

/// errors.json: the three summaries and an overall "pass" (docs/report.md).
nlohmann::ordered_json errors_json(const Comparison& comparison, const Thresholds& thresholds);

}  // namespace p3at::vipars::report
