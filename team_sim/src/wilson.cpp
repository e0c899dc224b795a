#include "p3at/team_sim/wilson.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::team_sim {

Interval wilson_interval(std::uint64_t successes, std::uint64_t trials, double z) {
  if (trials == 0) return {0.0, 1.0};
  successes = std::min(successes, trials);
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2n = z * z / n;
  // centre = (p + z²/2n) / (1 + z²/n); half-width = z/(1 + z²/n) · sqrt(p(1-p)/n + z²/4n²)
  const double denominator = 1.0 + z2n;
  const double centre = (p + z2n / 2.0) / denominator;
  const double half = z / denominator * std::sqrt(p * (1.0 - p) / n + z2n / (4.0 * n));
  Interval interval{std::clamp(centre - half, 0.0, 1.0), std::clamp(centre + half, 0.0, 1.0)};
  // At the edges the bound is exactly 0 or 1 in exact arithmetic; rounding
  // must not turn "never observed" into a tiny positive lower bound.
  if (successes == 0) interval.low = 0.0;
  if (successes == trials) interval.high = 1.0;
  return interval;
}

}  // namespace p3at::team_sim
