// The stuck share read along the entry error's axis (engine/stuck_profile.hpp):
// the probes find a narrow pinned band between strata that disagree, the
// integral of a piecewise-linear share against the normal density is exact,
// and the rebalanced quadrature keeps its mass, lending a wholly pinned
// stratum's escapees to its nearest neighbour that got through.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/stuck_profile.hpp"
#include "p3at/verifier/mog.hpp"

namespace engine = p3at::verifier::engine;
using p3at::verifier::normal_cdf;

constexpr double kInf = std::numeric_limits<double>::infinity();

namespace {

/// The strata's means as nodes of a share function.
template <typename F>
std::vector<engine::StuckNode> strata_nodes(F share) {
  std::vector<engine::StuckNode> nodes;
  for (const auto& s : engine::error_strata()) nodes.push_back({s.z, share(s.z), 0.0, 0.0});
  return nodes;
}

/// A finished path of one stratum.
engine::FinishedPath finished(std::uint8_t stratum, double weight) {
  engine::FinishedPath p;
  p.walker.stratum = stratum;
  p.walker.weight = weight;
  return p;
}

double finished_mass(const engine::NoiseQuadrature& q, std::uint8_t stratum) {
  double m = 0.0;
  for (const auto& p : q.finished) m += p.walker.stratum == stratum ? p.walker.weight : 0.0;
  return m;
}

}  // namespace

TEST_CASE("each stratum's slab holds its probability and its mean") {
  double total = 0.0;
  for (std::size_t k = 0; k < engine::kErrorStrata; ++k) {
    const engine::StratumSlab slab = engine::stratum_slab(k);
    const double lo = std::isfinite(slab.lo) ? normal_cdf(slab.lo) : 0.0;
    const double hi = std::isfinite(slab.hi) ? normal_cdf(slab.hi) : 1.0;
    CHECK(hi - lo == doctest::Approx(engine::error_strata()[k].weight).epsilon(1e-9));
    CHECK(engine::error_strata()[k].z > slab.lo);
    CHECK(engine::error_strata()[k].z < slab.hi);
    total += hi - lo;
  }
  CHECK(total == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("the integral of a piecewise-linear share against the normal density") {
  SUBCASE("a share of 1 everywhere gives each slab its probability") {
    const auto nodes = strata_nodes([](double) { return 1.0; });
    for (std::size_t k = 0; k < engine::kErrorStrata; ++k) {
      const engine::StratumSlab slab = engine::stratum_slab(k);
      CHECK(engine::stuck_mass_between(nodes, slab.lo, slab.hi) ==
            doctest::Approx(engine::error_strata()[k].weight).epsilon(1e-12));
    }
  }
  SUBCASE("a ramp from 0 at z = -1 to 1 at z = 1, against a fine sum") {
    const std::vector<engine::StuckNode> nodes{{-1.0, 0.0, 0, 0}, {1.0, 1.0, 0, 0}};
    double sum = 0.0;
    const double dz = 1e-4;
    for (double z = -6.0; z < 6.0; z += dz) {
      const double c = z + 0.5 * dz;
      const double s = c < -1.0 ? 0.0 : (c > 1.0 ? 1.0 : 0.5 * (c + 1.0));
      sum += s * std::exp(-0.5 * c * c) / std::sqrt(2.0 * 3.14159265358979323846) * dz;
    }
    CHECK(engine::stuck_mass_between(nodes, -kInf, kInf) == doctest::Approx(sum).epsilon(1e-6));
    CHECK(sum == doctest::Approx(0.5).epsilon(1e-6));  // odd about z = 0
  }
}

TEST_CASE("a narrow pinned band inside the middle slab is found and weighed by its own probability") {
  // The model pins z in [-0.1, 0.2] (a wall's end met head on) and the far
  // tail beyond -1.9: the middle stratum's mean is pinned, its neighbours are not.
  const auto share = [](double z) { return (z >= -0.1 && z <= 0.2) || z < -1.9 ? 1.0 : 0.0; };
  const double truth = normal_cdf(0.2) - normal_cdf(-0.1) + normal_cdf(-1.9);
  std::size_t probes = 0;
  const engine::StuckProbe probe = [&](double z) { return engine::StuckNode{z, share(z), 1.0, 2.0}; };
  engine::StuckProfileLimits limits;
  limits.max_probes = 40;
  const auto nodes = engine::refine_stuck_profile(strata_nodes(share), probe, limits, probes);
  const double mass = engine::stuck_mass_between(nodes, -kInf, kInf);
  MESSAGE("pinned mass " << mass << " against " << truth << " after " << probes << " probes");
  // The slabs alone said the middle stratum's 0.547 and the tail's 0.012.
  // Each step is located within limits.min_width, and the linear share
  // across it is off by at most half that interval's normal mass.
  const auto pdf = [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * 3.14159265358979323846); };
  const double bound = 0.5 * limits.min_width * (pdf(-0.1) + pdf(0.2) + pdf(-1.9));
  CHECK(std::abs(mass - truth) < bound);
  CHECK(bound < 0.025);
  CHECK(probes <= limits.max_probes);
  // Sorted, and every probe a new node.
  for (std::size_t i = 1; i < nodes.size(); ++i) CHECK(nodes[i].z > nodes[i - 1].z);
  CHECK(nodes.size() == engine::kErrorStrata + probes);
  SUBCASE("the budget caps the probes") {
    std::size_t few = 0;
    engine::StuckProfileLimits tight;
    tight.max_probes = 3;
    engine::refine_stuck_profile(strata_nodes(share), probe, tight, few);
    CHECK(few == 3);
  }
  SUBCASE("strata that agree cost no probe") {
    std::size_t none = 0;
    const auto agreeing = engine::refine_stuck_profile(strata_nodes([](double) { return 0.0; }), probe, limits, none);
    CHECK(none == 0);
    CHECK(agreeing.size() == engine::kErrorStrata);
  }
}

TEST_CASE("rebalancing keeps the mass and lends a pinned stratum's escapees to its nearest free neighbour") {
  // Stratum 0 pinned whole (0.5 of the mass), strata 1 and 2 finished.
  // Strata 1 (z > 0) and 2 (z < 0) are equally near stratum 0: the first
  // (1) takes its escapees.
  engine::NoiseQuadrature q;
  q.finished = {finished(1, 0.15), finished(1, 0.05), finished(2, 0.2)};
  q.stuck_by_stratum[0] = 0.5;
  q.stuck_x_by_stratum[0] = 0.5 * 3.0;
  q.stuck_y_by_stratum[0] = 0.5 * 4.0;
  q.stuck_by_stratum[3] = 0.1;
  q.stuck = 0.6;
  std::array<double, engine::kErrorStrata> target{};
  target[0] = 0.1;   // the band is a fifth of the slab
  target[2] = 0.05;  // stratum 2 pinned a quarter where the quadrature pinned none
  target[3] = 0.1;
  const std::vector<engine::StuckNode> nodes{{-1.07, 1.0, 7.0, 8.0}, {0.0, 1.0, 3.0, 4.0}};
  engine::rebalance_strata(q, target, nodes);
  double total = q.stuck;
  for (const auto& p : q.finished) total += p.walker.weight;
  CHECK(total == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(q.stuck == doctest::Approx(0.25).epsilon(1e-12));
  // Stratum 1 finishes its own 0.2 and stratum 0's 0.4, in its paths' proportions.
  CHECK(finished_mass(q, 1) == doctest::Approx(0.6).epsilon(1e-12));
  CHECK(q.finished[0].walker.weight == doctest::Approx(0.45).epsilon(1e-12));
  CHECK(finished_mass(q, 2) == doctest::Approx(0.15).epsilon(1e-12));
  // Where the pinned stand: stratum 0 where the quadrature pinned it,
  // stratum 2 at the pinned node nearest its slab (z = -1.07 is inside it).
  CHECK(q.stuck_x_by_stratum[2] / q.stuck_by_stratum[2] == doctest::Approx(7.0));
  CHECK(q.stuck_x_m == doctest::Approx(0.1 * 3.0 + 0.05 * 7.0 + 0.1 * 0.0).epsilon(1e-12));
  SUBCASE("nothing got through anywhere: a pinned stratum stays pinned") {
    engine::NoiseQuadrature all;
    all.stuck_by_stratum[0] = 1.0;
    all.stuck = 1.0;
    std::array<double, engine::kErrorStrata> less{};
    less[0] = 0.3;
    engine::rebalance_strata(all, less, nodes);
    CHECK(all.stuck == doctest::Approx(1.0));
  }
}
