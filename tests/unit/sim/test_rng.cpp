// The simulator's random numbers: the ziggurat Gaussian (Rng::normal) that
// the physics draws from has the normal distribution, tails included, is
// reproducible per seed, and draws nothing for a zero deviation.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "p3at/sim/rng.hpp"

using p3at::sim::Rng;

namespace {

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

}  // namespace

TEST_CASE("Rng::normal draws the normal distribution: moments, CDF and tails") {
  Rng rng(42, 7);
  constexpr int kDraws = 1'000'000;
  std::vector<double> x(kDraws);
  for (double& v : x) v = rng.normal(1.0);
  double m1 = 0.0, m2 = 0.0, m4 = 0.0;
  for (double v : x) {
    m1 += v;
    m2 += v * v;
    m4 += v * v * v * v;
  }
  m1 /= kDraws;
  m2 /= kDraws;
  m4 /= kDraws;
  // Standard errors for 10⁶ draws: mean 0.001, variance 0.0014, fourth moment 0.0098.
  CHECK(std::abs(m1) < 0.005);
  CHECK(m2 == doctest::Approx(1.0).epsilon(0.007));
  CHECK(m4 == doctest::Approx(3.0).epsilon(0.017));
  // Kolmogorov-Smirnov distance to Φ: the 1 % critical value is 1.63 / sqrt(n).
  std::sort(x.begin(), x.end());
  double ks = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = normal_cdf(x[i]);
    ks = std::max({ks, std::abs(f - static_cast<double>(i) / kDraws), std::abs(f - static_cast<double>(i + 1) / kDraws)});
  }
  CHECK(ks < 1.63 / std::sqrt(static_cast<double>(kDraws)));
  // Both tails beyond the ziggurat's base (r = 3.654): P = 2.58e-4, about 258 ± 16.
  const auto beyond = std::count_if(x.begin(), x.end(), [](double v) { return std::abs(v) > 3.6541528853610088; });
  CHECK(beyond > 258 - 5 * 16);
  CHECK(beyond < 258 + 5 * 16);
  // And symmetric: as many far below as far above (3 sd of a binomial(n, 1/2)).
  const auto below_minus_2 = std::count_if(x.begin(), x.end(), [](double v) { return v < -2.0; });
  const auto above_plus_2 = std::count_if(x.begin(), x.end(), [](double v) { return v > 2.0; });
  CHECK(std::abs(static_cast<double>(below_minus_2 - above_plus_2)) < 3.0 * std::sqrt(2.0 * 22750.0));
}

TEST_CASE("Rng::normal scales by sd, repeats per seed, and draws nothing for sd 0") {
  Rng a(9, 1), b(9, 1), c(10, 1);
  std::vector<double> xa, xb, xc;
  for (int i = 0; i < 1000; ++i) {
    xa.push_back(a.normal(0.5));
    xb.push_back(b.normal(0.5));
    xc.push_back(c.normal(0.5));
    CHECK(a.normal(0.0) == 0.0);  // consumes nothing: a and b stay in step
  }
  CHECK(xa == xb);
  CHECK(xa != xc);
  double var = 0.0;
  for (double v : xa) var += v * v;
  CHECK(std::sqrt(var / 1000.0) == doctest::Approx(0.5).epsilon(0.1));
}
