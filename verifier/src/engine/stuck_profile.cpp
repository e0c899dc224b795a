#include "engine/stuck_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {
namespace {

// What rounding leaves of a stratum (of its own mass) is taken as none.
constexpr double kMinStuckShare = 1e-6;

bool by_z(const StuckNode& a, const StuckNode& b) { return a.z < b.z; }

/// normal_cdf that takes the infinities the outer slabs have.
double cdf(double z) {
  if (z == -std::numeric_limits<double>::infinity()) return 0.0;
  if (z == std::numeric_limits<double>::infinity()) return 1.0;
  return normal_cdf(z);
}
double pdf(double z) { return std::isfinite(z) ? normal_pdf(z) : 0.0; }

/// The integral over [l, u] of (a + b z) phi(z) dz (b = 0 where l or u is infinite).
double linear_times_normal(double a, double b, double l, double u) {
  if (!(u > l)) return 0.0;
  return a * (cdf(u) - cdf(l)) + b * (pdf(l) - pdf(u));
}

/// Where a pinned mass stands on average: its location sums over its mass
/// (the origin for no mass; the caller decides what that means).
StuckNode pinned_node(double z, double share, double mass, double sum_x, double sum_y) {
  StuckNode n{z, share, 0.0, 0.0};
  if (mass > 0.0) {
    n.x_m = sum_x / mass;
    n.y_m = sum_y / mass;
  }
  return n;
}

/// Each stratum's mass: its finished paths' weights plus what it has pinned.
std::array<double, kErrorStrata> stratum_totals(const NoiseQuadrature& quad, std::array<double, kErrorStrata>& finished) {
  finished = {};
  for (const FinishedPath& p : quad.finished) finished[p.walker.stratum] += p.walker.weight;
  std::array<double, kErrorStrata> total{};
  for (std::size_t k = 0; k < kErrorStrata; ++k) total[k] = finished[k] + quad.stuck_by_stratum[k];
  return total;
}

}  // namespace

std::vector<StuckNode> refine_stuck_profile(std::vector<StuckNode> nodes, const StuckProbe& probe,
                                            const StuckProfileLimits& limits, std::size_t& probes_made) {
  std::sort(nodes.begin(), nodes.end(), by_z);
  while (probes_made < limits.max_probes && nodes.size() >= 2) {
    // The heaviest disagreement still wider than the resolution.
    double best = limits.min_mass;
    std::size_t at = nodes.size();
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
      const double width = nodes[i + 1].z - nodes[i].z;
      const double disagreement = std::abs(nodes[i + 1].share - nodes[i].share);
      if (!(width > limits.min_width) || !(disagreement > limits.min_disagreement)) continue;
      const double score = disagreement * (cdf(nodes[i + 1].z) - cdf(nodes[i].z));
      if (score > best) {
        best = score;
        at = i;
      }
    }
    if (at == nodes.size()) break;
    StuckNode mid = probe(0.5 * (nodes[at].z + nodes[at + 1].z));
    ++probes_made;
    mid.share = std::clamp(mid.share, 0.0, 1.0);
    nodes.insert(nodes.begin() + static_cast<std::ptrdiff_t>(at + 1), mid);
  }
  return nodes;
}

double stuck_mass_between(std::vector<StuckNode> nodes, double lo, double hi) {
  if (nodes.empty() || !(hi > lo)) return 0.0;
  std::sort(nodes.begin(), nodes.end(), by_z);
  // Constant below the first node and above the last.
  double mass = linear_times_normal(nodes.front().share, 0.0, lo, std::min(hi, nodes.front().z));
  mass += linear_times_normal(nodes.back().share, 0.0, std::max(lo, nodes.back().z), hi);
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    const StuckNode& p = nodes[i];
    const StuckNode& q = nodes[i + 1];
    const double l = std::max(lo, p.z), u = std::min(hi, q.z);
    if (!(u > l) || !(q.z > p.z)) continue;
    const double b = (q.share - p.share) / (q.z - p.z);
    mass += linear_times_normal(p.share - b * p.z, b, l, u);
  }
  return std::max(0.0, mass);
}

void rebalance_strata(NoiseQuadrature& quad, const std::array<double, kErrorStrata>& target_stuck,
                      const std::vector<StuckNode>& nodes) {
  std::array<double, kErrorStrata> finished{}, target{};
  const std::array<double, kErrorStrata> total = stratum_totals(quad, finished);
  for (std::size_t k = 0; k < kErrorStrata; ++k) target[k] = std::clamp(target_stuck[k], 0.0, total[k]);
  // What each stratum lets through, and who finishes it for a stratum the
  // quadrature pinned whole.
  std::array<double, kErrorStrata> through{};
  for (std::size_t k = 0; k < kErrorStrata; ++k) {
    // What rounding leaves of a stratum the target pins whole is pinned too:
    // paths weighing 1e-17 of their stratum are no outcome worth stepping on.
    if (total[k] - target[k] < kMinStuckShare * total[k]) target[k] = total[k];
    const double passing = total[k] - target[k];
    if (finished[k] > 0.0) {
      through[k] += passing;
      continue;
    }
    if (!(passing > 0.0)) continue;
    std::size_t nearest = kErrorStrata;
    for (std::size_t j = 0; j < kErrorStrata; ++j) {
      if (!(finished[j] > 0.0)) continue;
      if (nearest == kErrorStrata ||
          std::abs(error_strata()[j].z - error_strata()[k].z) < std::abs(error_strata()[nearest].z - error_strata()[k].z)) {
        nearest = j;
      }
    }
    if (nearest == kErrorStrata) {
      target[k] = total[k];  // nothing got through anywhere: nothing to lend
      continue;
    }
    through[nearest] += passing;
  }
  for (FinishedPath& p : quad.finished) {
    // A stratum whose paths all weigh nothing (underflowed) lent nothing and keeps them.
    const std::size_t k = p.walker.stratum;
    if (finished[k] > 0.0) p.walker.weight *= through[k] / finished[k];
  }
  std::erase_if(quad.finished, [](const FinishedPath& p) { return !(p.walker.weight > 0.0); });
  // The pinned mass and where it stands.
  double stuck = 0.0, x = 0.0, y = 0.0;
  for (std::size_t k = 0; k < kErrorStrata; ++k) {
    if (!(target[k] > 0.0)) {
      quad.stuck_by_stratum[k] = quad.stuck_x_by_stratum[k] = quad.stuck_y_by_stratum[k] = 0.0;
      continue;
    }
    const StuckNode own =
        pinned_node(0.0, 0.0, quad.stuck_by_stratum[k], quad.stuck_x_by_stratum[k], quad.stuck_y_by_stratum[k]);
    double px = own.x_m, py = own.y_m;
    if (!(quad.stuck_by_stratum[k] > 0.0)) {
      // The pinned node nearest the slab (inside it: distance 0).
      const StratumSlab slab = stratum_slab(k);
      double nearest = std::numeric_limits<double>::infinity();
      for (const StuckNode& n : nodes) {
        if (!(n.share > 0.0)) continue;
        const double d = n.z < slab.lo ? slab.lo - n.z : (n.z > slab.hi ? n.z - slab.hi : 0.0);
        if (d < nearest) {
          nearest = d;
          px = n.x_m;
          py = n.y_m;
        }
      }
    }
    quad.stuck_by_stratum[k] = target[k];
    quad.stuck_x_by_stratum[k] = target[k] * px;
    quad.stuck_y_by_stratum[k] = target[k] * py;
    stuck += target[k];
    x += target[k] * px;
    y += target[k] * py;
  }
  quad.stuck = stuck;
  quad.stuck_x_m = x;
  quad.stuck_y_m = y;
}

std::size_t read_stuck_along_axis(const PathStepper& stepper, const std::vector<Walker>& unsplit,
                                  const Eigen::Vector3d& axis, std::int64_t persistence, std::size_t directions,
                                  std::size_t cap, NoiseQuadrature& quad) {
  std::array<double, kErrorStrata> finished{};
  const std::array<double, kErrorStrata> total = stratum_totals(quad, finished);
  // The strata by z, each with its main-run share.
  std::vector<std::size_t> order;
  std::vector<StuckNode> nodes(kErrorStrata);
  for (std::size_t k = 0; k < kErrorStrata; ++k) {
    const double stuck = quad.stuck_by_stratum[k];
    nodes[k] = pinned_node(error_strata()[k].z, total[k] > 0.0 ? stuck / total[k] : 0.0, stuck,
                           quad.stuck_x_by_stratum[k], quad.stuck_y_by_stratum[k]);
    if (total[k] > 0.0) order.push_back(k);
  }
  std::sort(order.begin(), order.end(),
            [](std::size_t a, std::size_t b) { return error_strata()[a].z < error_strata()[b].z; });
  std::size_t cycles = 0, probes = 0;
  const StuckProbe probe = [&](double z) {
    const NoiseQuadrature q =
        noise_quadrature(stepper, shifted_along(unsplit, axis, z), persistence, directions, directions, directions, cap);
    cycles += q.cycles_simulated;
    return pinned_node(z, q.stuck, q.stuck, q.stuck_x_m, q.stuck_y_m);
  };
  // Only a band: a stratum mostly pinned between two that mostly get
  // through (an edge keeps its slabs: the header says why).
  std::array<double, kErrorStrata> target = quad.stuck_by_stratum;
  std::vector<StuckNode> read;
  for (std::size_t i = 1; i + 1 < order.size(); ++i) {
    const std::size_t k = order[i];
    if (!(nodes[k].share >= 0.5) || !(nodes[order[i - 1]].share < 0.5) || !(nodes[order[i + 1]].share < 0.5)) continue;
    const std::vector<StuckNode> band =
        refine_stuck_profile({nodes[order[i - 1]], nodes[k], nodes[order[i + 1]]}, probe, StuckProfileLimits{}, probes);
    const StratumSlab slab = stratum_slab(k);
    target[k] = total[k] * stuck_mass_between(band, slab.lo, slab.hi) / error_strata()[k].weight;
    read.insert(read.end(), band.begin(), band.end());
  }
  if (read.empty()) return 0;
  rebalance_strata(quad, target, read);
  return cycles;
}

}  // namespace p3at::verifier::engine
