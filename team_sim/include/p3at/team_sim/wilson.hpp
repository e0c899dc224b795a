#pragma once
/// Confidence intervals for a proportion estimated from independent runs.
///
/// The Wilson score interval (Wilson 1927) is used rather than the textbook
/// p ± z·sqrt(p(1-p)/n) because validation campaigns routinely see 0 or n
/// successes (P(t <= 180 s) = 0 in the Bounding Overwatch example), where the
/// textbook interval collapses to a single point and claims certainty; the
/// Wilson interval stays inside [0, 1] and keeps a sensible width there.

#include <cstdint>

namespace p3at::team_sim {

/// The two-sided 95 % normal quantile, z such that P(|N(0,1)| <= z) = 0.95.
inline constexpr double kZ95 = 1.959963984540054;

struct Interval {
  double low = 0.0;
  double high = 1.0;
};

/// Wilson score interval for `successes` out of `trials` at normal quantile z.
/// No trials: [0, 1] (nothing is known). 0 successes: low is exactly 0;
/// `trials` successes: high is exactly 1. Requires successes <= trials.
Interval wilson_interval(std::uint64_t successes, std::uint64_t trials, double z = kZ95);

}  // namespace p3at::team_sim
