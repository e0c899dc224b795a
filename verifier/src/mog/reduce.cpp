// Keeping mixtures small: Runnalls' greedy merge, and mixtures built from
// weighted points. Both merge by moment matching, so the whole mixture's mean
// and variance are what they were (up to rounding).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {
namespace {

// Below this share of the total weight a component cannot change any
// probability the verifier reports (it works to about 1e-6).
constexpr double kDropWeight = 1e-12;
// Variances only inside the merge cost's logarithms: a point mass has var 0,
// and log(0) would make every merge with it infinitely expensive.
constexpr double kCostVarFloor = 1e-18;

// The single Gaussian with the pair's total weight, mean and variance.
Component1 merged(const Component1& a, const Component1& b) {
  const double w = a.weight + b.weight;
  if (!(w > 0.0)) return Component1{0.0, 0.5 * (a.mean + b.mean), 0.5 * (a.var + b.var)};
  const double pa = a.weight / w;
  const double pb = b.weight / w;
  const double d = a.mean - b.mean;
  return Component1{w, pa * a.mean + pb * b.mean, pa * a.var + pb * b.var + pa * pb * d * d};
}

// The logarithm of a variance as the merge cost takes it.
double log_var(double var) { return std::log(std::max(var, kCostVarFloor)); }

// Runnalls' (2007) upper bound on the KL divergence a merge adds:
// B = 0.5 [(wa + wb) log v_ab - wa log va - wb log vb], with log va and log vb
// given (reduce() keeps them per component: the logarithms were a tenth of
// the relay benchmark's CPU).
double merge_cost(const Component1& a, const Component1& b, double log_var_a, double log_var_b) {
  const Component1 m = merged(a, b);
  return 0.5 * (m.weight * log_var(m.var) - a.weight * log_var_a - b.weight * log_var_b);
}

double merge_cost(const Component1& a, const Component1& b) {
  return merge_cost(a, b, log_var(a.var), log_var(b.var));
}

// A total order on components, so results never depend on input order.
bool before(const Component1& a, const Component1& b) {
  return std::tie(a.mean, a.var, a.weight) < std::tie(b.mean, b.var, b.weight);
}

void sort_by_mean(std::vector<Component1>& components) {
  std::stable_sort(components.begin(), components.end(), before);
}

}  // namespace

void reduce(Mixture1& x, std::size_t max_components) {
  std::vector<Component1>& c = x.components;
  if (c.empty()) return;
  const std::size_t limit = std::max<std::size_t>(max_components, 1);

  // Sorted first, so that even the rounding of the sums below does not
  // depend on the order the components came in.
  sort_by_mean(c);
  double total = 0.0;
  for (const Component1& component : c) total += component.weight;
  if (!(total > 0.0)) {
    c.clear();  // no weight at all: no distribution
    return;
  }
  std::erase_if(c, [total](const Component1& component) { return !(component.weight / total >= kDropWeight); });
  x.normalise();
  if (c.size() <= limit) return;

  // Runnalls' greedy merge restricted to neighbours in mean order: in one
  // dimension the cheapest pair is (nearly always) adjacent, and this keeps a
  // reduction of n components at O(n^2) comparisons with only O(n) cost
  // evaluations (the verifier reduces 64 -> 8 at every event). `next`/`prev`
  // link the live components in mean order; cost[i] is the cost of merging i
  // with its live successor.
  const std::size_t n = c.size();
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> next(n), prev(n);
  std::vector<double> cost(n, std::numeric_limits<double>::infinity());
  std::vector<double> log_vars(n);
  for (std::size_t i = 0; i < n; ++i) log_vars[i] = log_var(c[i].var);
  const auto cost_after = [&c, &log_vars](std::size_t i, std::size_t j) {
    return merge_cost(c[i], c[j], log_vars[i], log_vars[j]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    next[i] = i + 1 < n ? i + 1 : kNone;
    prev[i] = i > 0 ? i - 1 : kNone;
    if (next[i] != kNone) cost[i] = cost_after(i, next[i]);
  }
  std::size_t live = n;
  while (live > limit) {
    // Cheapest adjacent pair, walking the live list (component 0 is never
    // merged away, and the list runs in index order); a strict '<' keeps the
    // lowest index on ties. Walking only the live ones, without a flag per
    // component, halves this loop, a fifth of the relay benchmark's CPU.
    std::size_t best = 0;
    for (std::size_t i = next[0]; next[i] != kNone; i = next[i]) {
      if (cost[i] < cost[best]) best = i;
    }
    const std::size_t gone = next[best];
    c[best] = merged(c[best], c[gone]);
    log_vars[best] = log_var(c[best].var);
    next[best] = next[gone];
    if (next[gone] != kNone) prev[next[gone]] = best;
    --live;
    cost[best] = next[best] != kNone ? cost_after(best, next[best]) : std::numeric_limits<double>::infinity();
    if (prev[best] != kNone) cost[prev[best]] = cost_after(prev[best], best);
  }
  std::vector<Component1> kept;
  kept.reserve(live);
  for (std::size_t i = 0; i != kNone; i = next[i]) kept.push_back(c[i]);
  c = std::move(kept);
  sort_by_mean(c);
}

Mixture1 from_weighted_points(const std::vector<double>& values, const std::vector<double>& weights,
                              std::size_t max_components) {
  if (values.size() != weights.size()) {
    throw std::invalid_argument("from_weighted_points: " + std::to_string(values.size()) + " values but " +
                                std::to_string(weights.size()) + " weights");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || !std::isfinite(weights[i]) || weights[i] < 0.0) {
      throw std::invalid_argument("from_weighted_points: point " + std::to_string(i) +
                                  " needs a finite value and a finite weight >= 0");
    }
  }
  // One point mass per point with weight, in value order (ties by index).
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&values](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<Component1> groups;
  for (std::size_t i : order) {
    if (weights[i] <= 0.0) continue;
    // Equal values are one point mass.
    if (!groups.empty() && groups.back().mean == values[i]) {
      groups.back().weight += weights[i];
    } else {
      groups.push_back(Component1{weights[i], values[i], 0.0});
    }
  }
  Mixture1 out{std::move(groups)};
  out.normalise();

  // Merge neighbours (in value order) by Runnalls' cost until few enough
  // remain: every group is a run of consecutive sorted points, moment-matched.
  const std::size_t limit = std::max<std::size_t>(max_components, 1);
  std::vector<Component1>& g = out.components;
  while (g.size() > limit) {
    std::size_t best = 0;
    double best_cost = merge_cost(g[0], g[1]);
    for (std::size_t i = 1; i + 1 < g.size(); ++i) {
      const double cost = merge_cost(g[i], g[i + 1]);
      if (cost < best_cost) {
        best_cost = cost;
        best = i;
      }
    }
    g[best] = merged(g[best], g[best + 1]);
    g.erase(g.begin() + static_cast<std::ptrdiff_t>(best + 1));
  }
  return out;
}

}  // namespace p3at::verifier
