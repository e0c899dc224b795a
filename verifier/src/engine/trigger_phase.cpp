#include "engine/trigger_phase.hpp"

#include <algorithm>
#include <cmath>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {

double expected_check_gap(double t, double sd) {
  if (!(sd > 1e-9)) {
    const double gap = std::ceil(t) - t;
    return gap > 0.0 ? gap : 1.0;  // exactly on a check: it fires there... one check later for a crossing just after
  }
  if (sd > 3.0) return 0.5;  // the fraction is uniform to far below 1e-6
  // Sum over the cells (k - 1, k]: P(cell) * (k - E[X | cell]).
  const double lo = std::floor(t - 8.0 * sd), hi = std::ceil(t + 8.0 * sd);
  double total = 0.0, mass = 0.0;
  for (double k = lo + 1.0; k <= hi; k += 1.0) {
    const double a = (k - 1.0 - t) / sd, b = (k - t) / sd;
    const double p = normal_cdf(b) - normal_cdf(a);
    if (!(p > 1e-15)) continue;
    const double mean = t + sd * (normal_pdf(a) - normal_pdf(b)) / p;
    total += p * (k - mean);
    mass += p;
  }
  return mass > 0.0 ? total / mass : 0.5;
}

double check_gap_variance(double t, double sd) {
  if (!(sd > 1e-9)) return 0.0;
  if (sd > 3.0) return 1.0 / 12.0;
  // Per cell (k - 1, k], X is a truncated normal: E[(k - X)^2 | cell] is
  // (k - E[X | cell])^2 + Var[X | cell].
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
  if (!(mass > 0.0)) return 1.0 / 12.0;
  const double m = first / mass;
  return std::max(second / mass - m * m, 0.0);
}

}  // namespace p3at::verifier::engine
