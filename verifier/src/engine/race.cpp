#include "engine/race.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace p3at::verifier::engine {
namespace {

/// Every component's mean -/+ 8 standard deviations.
std::pair<double, double> span_of(const Mixture1& x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Component1& c : x.components) {
    const double reach = 8.0 * std::sqrt(std::max(c.var, 0.0));
    lo = std::min(lo, c.mean - reach);
    hi = std::max(hi, c.mean + reach);
  }
  return {lo, hi};
}

}  // namespace

std::vector<double> first_probabilities(const std::vector<const Mixture1*>& xs) {
  constexpr int kCells = 1000;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Mixture1* x : xs) {
    const auto [a, b] = span_of(*x);
    lo = std::min(lo, a);
    hi = std::max(hi, b);
  }
  std::vector<double> out(xs.size(), 0.0);
  if (xs.empty() || !(hi >= lo)) return out;
  if (!(hi > lo)) {  // every time the same point: one cell around it
    lo -= 1.0;
    hi += 1.0;
  }
  const double h = (hi - lo) / kCells;
  // The CDF split into the part from point masses (ties: decided by order)
  // and the continuous rest (averaged over the cell: no bias of order h).
  const auto parts = [&](const Mixture1& x, double t, double& points, double& smooth) {
    double total = 0.0;
    points = smooth = 0.0;
    for (const Component1& c : x.components) {
      total += c.weight;
      if (c.var > 0.0) smooth += c.weight * normal_cdf((t - c.mean) / std::sqrt(c.var));
      else if (c.mean <= t) points += c.weight;
    }
    if (total > 0.0) {
      points /= total;
      smooth /= total;
    }
  };
  const std::size_t n = xs.size();
  std::vector<double> prev_pt(n), prev_sm(n), next_pt(n), next_sm(n);
  for (std::size_t c = 0; c < n; ++c) parts(*xs[c], lo, prev_pt[c], prev_sm[c]);
  for (int k = 1; k <= kCells; ++k) {
    const double t = lo + h * k;
    for (std::size_t c = 0; c < n; ++c) parts(*xs[c], t, next_pt[c], next_sm[c]);
    for (std::size_t c = 0; c < n; ++c) {
      const double mass = (next_pt[c] + next_sm[c]) - (prev_pt[c] + prev_sm[c]);
      if (!(mass > 0.0)) continue;
      // Not fired yet: at the cell's middle. Point masses of different
      // robots in one cell are a tie of the quadrature (identical legs give
      // identical nodes), which real runs, continuous, split evenly.
      double others = 1.0;
      for (std::size_t o = 0; o < n && others > 0.0; ++o) {
        if (o == c) continue;
        const double fired = 0.5 * (prev_sm[o] + next_sm[o]) + 0.5 * (prev_pt[o] + next_pt[o]);
        others *= std::max(0.0, 1.0 - fired);
      }
      out[c] += mass * others;
    }
    prev_pt.swap(next_pt);
    prev_sm.swap(next_sm);
  }
  return out;
}

}  // namespace p3at::verifier::engine
