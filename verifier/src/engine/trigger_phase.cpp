#include "engine/trigger_phase.hpp"

#include <algorithm>
#include <cmath>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {

CheckGap check_gap(double t, double sd) {
  if (!(sd > 1e-9)) {
    const double gap = std::ceil(t) - t;
    // Exactly on a check: it fires there... one check later for a crossing just after.
    return {gap > 0.0 ? gap : 1.0, 0.0};
  }
  if (sd > 3.0) return {0.5, 1.0 / 12.0};  // the fraction is uniform to far below 1e-6
  // Per cell (k - 1, k], X is a truncated normal: P(cell), E[k - X | cell]
  // and E[(k - X)^2 | cell] = (k - E[X | cell])^2 + Var[X | cell].
  const double lo = std::floor(t - 8.0 * sd), hi = std::ceil(t + 8.0 * sd);
  double first = 0.0, second = 0.0, mass = 0.0;
  for (double k = lo + 1.0; k <= hi; k += 1.0) {
    const double a = (k - 1.0 - t) / sd, b = (k - t) / sd;
    const double p = normal_cdf(b) - normal_cdf(a);
    if (!(p > 1e-15)) continue;
    const double r = (normal_pdf(a) - normal_pdf(b)) / p;
    const double mean = t + sd * r;
    const double var = sd * sd * std::max(0.0, 1.0 + (a * normal_pdf(a) - b * normal_pdf(b)) / p - r * r);
    first += p * (k - mean);
    second += p * ((k - mean) * (k - mean) + var);
    mass += p;
  }
  if (!(mass > 0.0)) return {};
  const double m = first / mass;
  return {m, std::max(second / mass - m * m, 0.0)};
}

std::vector<CheckShare> check_shares(double t, double sd) {
  if (!(sd > 0.0)) return {{std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(t))), 1.0}};
  std::vector<CheckShare> out;
  const auto first = static_cast<std::int64_t>(std::floor(t - 8.0 * sd));
  const auto last = static_cast<std::int64_t>(std::ceil(t + 8.0 * sd)) + 1;
  for (std::int64_t n = std::max<std::int64_t>(first, 1); n <= last; ++n) {
    const double nd = static_cast<double>(n);
    const double share = normal_cdf((nd - t) / sd) - normal_cdf((nd - 1.0 - t) / sd);
    if (share > 1e-12) out.push_back({n, share});
  }
  return out;
}

double expected_check_gap(double t, double sd) { return check_gap(t, sd).mean; }

double check_gap_variance(double t, double sd) { return check_gap(t, sd).var; }

}  // namespace p3at::verifier::engine
