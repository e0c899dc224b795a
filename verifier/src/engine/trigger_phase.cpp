#include "engine/trigger_phase.hpp"

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

}  // namespace p3at::verifier::engine
