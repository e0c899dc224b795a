#include "engine/direction_arcs.hpp"

#include <algorithm>

namespace p3at::verifier::engine {
std::vector<double> direction_arcs(const std::vector<double>& angles, const std::vector<DrawOutcome>& outcomes,
                                   const DrawProbe& probe, const DirectionArcLimits& limits, std::size_t& probes_made,
                                   std::vector<double>* boundaries) {
  const std::size_t n = angles.size();
  std::vector<double> equal(n, n > 0 ? 1.0 / static_cast<double>(n) : 0.0);
  if (n < 2 || outcomes.size() != n) return equal;
  if (std::all_of(outcomes.begin(), outcomes.end(), [&](DrawOutcome o) { return o == outcomes.front(); })) return equal;
  // boundary[j]: between direction j and j + 1 (the last one wraps a turn on).
  std::vector<double> boundary(n);
  std::size_t made = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t k = (j + 1) % n;
    double lo = angles[j], hi = angles[k] + (k == 0 ? kTurnRad : 0.0);
    if (outcomes[j] != outcomes[k]) {
      for (std::size_t d = 0; d < limits.depth && made < limits.max_probes; ++d) {
        const double mid = 0.5 * (lo + hi);
        const DrawOutcome o = probe(mid);
        ++made;
        // A third outcome between them is counted on the far side: the
        // near direction's arc ends before it.
        if (o == outcomes[j]) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
    }
    boundary[j] = 0.5 * (lo + hi);
  }
  probes_made += made;
  if (boundaries != nullptr) *boundaries = boundary;
  std::vector<double> share(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double left = j == 0 ? boundary[n - 1] - kTurnRad : boundary[j - 1];
    share[j] = std::max(0.0, boundary[j] - left) / kTurnRad;
  }
  return share;
}

}  // namespace p3at::verifier::engine
