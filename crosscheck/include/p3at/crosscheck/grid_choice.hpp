#pragma once
/// The grid a mission is cross-checked on: Tmax and Rmax axes that span
/// where P(t <= Tmax) and P(every r <= Rmax) rise from 0 to 1, for the
/// verifier or the validation runs, whichever rises earlier and ends later
/// (so a verifier that is wrong about where the curve rises cannot choose a
/// grid that hides it). Axes are A:B:STEP with a round step, so
/// `vipars verify --tmax-range A:B:STEP` gives the same grid.

#include <cstddef>
#include <string>
#include <vector>

namespace p3at::crosscheck {

struct Axis {
  double first = 0.0, last = 0.0, step = 1.0;
  std::vector<double> values;   ///< first, first + step, ... last (rounded to 15 significant digits)
  std::string range() const;    ///< "A:B:STEP"
};

/// Where a curve rises: from the last axis value at which it is still within
/// `tail` of its smallest value to the first at which it is within `tail` of
/// its largest. found = false for a flat or empty curve.
struct Rise {
  double lo = 0.0, hi = 0.0;
  bool found = false;
};
Rise rise_of_curve(const std::vector<double>& axis, const std::vector<double>& p, double tail = 0.001);
/// The same for a sample (completion times, distances): its `tail` and
/// 1 - `tail` quantiles of the finite values. found = false without any.
Rise rise_of_sample(std::vector<double> values, double tail = 0.001);

/// An axis from lo to hi (padded by 4 % of the span on each side, never
/// below `floor_value`) with a step of 1, 2, 2.5 or 5 times a power of ten,
/// the smallest that keeps it within `count` values.
Axis nice_axis(double lo, double hi, std::size_t count, double floor_value);

/// A value rounded to 15 significant digits (as `vipars verify`'s A:B:STEP parser rounds).
double round15(double x);

}  // namespace p3at::crosscheck
