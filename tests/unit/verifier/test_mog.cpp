// The mixture-of-Gaussians library against closed forms and against direct
// numerical integration of the densities involved (nothing here samples).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <Eigen/LU>

#include "p3at/verifier/mog.hpp"

namespace {

using p3at::verifier::Component1;
using p3at::verifier::Gaussian2;
using p3at::verifier::Mixture1;
using p3at::verifier::normal_cdf;
using p3at::verifier::normal_pdf;

// Composite Simpson's rule with n (even) intervals.
double integrate(const std::function<double(double)>& f, double lo, double hi, int n = 20000) {
  const double h = (hi - lo) / n;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) sum += f(lo + h * i) * (i % 2 == 1 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

double gaussian_pdf(double x, double mean, double var) {
  const double s = std::sqrt(var);
  return normal_pdf((x - mean) / s) / s;
}

double gaussian_cdf(double x, double mean, double var) { return normal_cdf((x - mean) / std::sqrt(var)); }

// Mean and variance of the density proportional to `density` on [lo, hi], and its mass.
struct NumericMoments {
  double mass, mean, var;
};
NumericMoments moments_of(const std::function<double(double)>& density, double lo, double hi) {
  const double mass = integrate(density, lo, hi);
  const double mean = integrate([&](double x) { return x * density(x); }, lo, hi) / mass;
  const double var = integrate([&](double x) { return (x - mean) * (x - mean) * density(x); }, lo, hi) / mass;
  return NumericMoments{mass, mean, var};
}

Mixture1 two_components() { return Mixture1{{Component1{0.25, -1.0, 0.5}, Component1{0.75, 3.0, 2.0}}}; }

}  // namespace

TEST_SUITE("normal helpers") {
  TEST_CASE("standard values, and full relative accuracy in the lower tail") {
    CHECK(normal_cdf(0.0) == 0.5);
    CHECK(normal_cdf(1.959963984540054) == doctest::Approx(0.975).epsilon(1e-14));
    CHECK(normal_cdf(-1.0) == doctest::Approx(0.15865525393145705).epsilon(1e-14));
    // Phi(-10) and Phi(-30): 1 - Phi(10) would have cancelled to 0.
    CHECK(normal_cdf(-10.0) == doctest::Approx(7.619853024160527e-24).epsilon(1e-12));
    CHECK(normal_cdf(-30.0) == doctest::Approx(4.906713927148187e-198).epsilon(1e-12));
    CHECK(normal_pdf(0.0) == doctest::Approx(1.0 / std::sqrt(2.0 * std::numbers::pi)).epsilon(1e-15));
    CHECK(normal_pdf(2.0) == doctest::Approx(0.05399096651318806).epsilon(1e-14));
  }

  TEST_CASE("normal_quantile inverts normal_cdf, in both tails, and is infinite at 0 and 1") {
    using p3at::verifier::normal_quantile;
    CHECK(normal_quantile(0.5) == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(normal_quantile(0.975) == doctest::Approx(1.959963984540054).epsilon(1e-12));
    CHECK(normal_quantile(0.15865525393145705) == doctest::Approx(-1.0).epsilon(1e-12));
    for (const double z : {-30.0, -10.0, -3.0, -0.3, 0.01, 1.0, 4.0}) {
      INFO("z = " << z);
      CHECK(normal_quantile(normal_cdf(z)) == doctest::Approx(z).epsilon(1e-9));
    }
    CHECK(std::isinf(normal_quantile(0.0)));
    CHECK(normal_quantile(0.0) < 0.0);
    CHECK(std::isinf(normal_quantile(1.0)));
    CHECK(normal_quantile(1.0) > 0.0);
    CHECK(std::isnan(normal_quantile(std::numeric_limits<double>::quiet_NaN())));
  }
}

TEST_SUITE("Mixture1") {
  TEST_CASE("moments and CDF of a two-component mixture") {
    const Mixture1 x = two_components();
    CHECK(x.mean() == doctest::Approx(0.25 * -1.0 + 0.75 * 3.0));
    // E[X^2] - E[X]^2 by hand: 0.25 (0.5 + 1) + 0.75 (2 + 9) - 2^2.
    CHECK(x.variance() == doctest::Approx(0.25 * 1.5 + 0.75 * 11.0 - 4.0));
    CHECK(x.cdf(1.0) == doctest::Approx(0.25 * gaussian_cdf(1.0, -1.0, 0.5) + 0.75 * gaussian_cdf(1.0, 3.0, 2.0)));
  }
  TEST_CASE("a point mass counts as <= itself") {
    const Mixture1 p = Mixture1::point(2.0);
    CHECK(p.cdf(2.0) == 1.0);
    CHECK(p.cdf(std::nextafter(2.0, 0.0)) == 0.0);
    CHECK(p.mean() == 2.0);
    CHECK(p.variance() == 0.0);
  }
  TEST_CASE("the empty mixture is no distribution") {
    const Mixture1 empty;
    CHECK(std::isnan(empty.mean()));
    CHECK(std::isnan(empty.variance()));
    CHECK(empty.cdf(1.0) == 0.0);
  }
  TEST_CASE("normalise and shifted") {
    Mixture1 x{{Component1{2.0, 0.0, 1.0}, Component1{6.0, 1.0, 1.0}}};
    x.normalise();
    CHECK(x.components[0].weight == 0.25);
    CHECK(x.components[1].weight == 0.75);
    const Mixture1 y = p3at::verifier::shifted(x, 10.0);
    CHECK(y.components[0].mean == 10.0);
    CHECK(y.components[1].mean == 11.0);
    CHECK(y.variance() == doctest::Approx(x.variance()));
  }
}

TEST_SUITE("sum") {
  TEST_CASE("of two Gaussians is the Gaussian with summed moments") {
    const Mixture1 s = p3at::verifier::sum(Mixture1::gaussian(1.0, 2.0), Mixture1::gaussian(3.0, 4.0), 8);
    REQUIRE(s.components.size() == 1);
    CHECK(s.components[0] == Component1{1.0, 4.0, 6.0});
  }
  TEST_CASE("of mixtures: every pair when the bound allows, the exact moments always") {
    const Mixture1 x = two_components();
    const Mixture1 y{{Component1{0.5, 10.0, 1.0}, Component1{0.5, 20.0, 3.0}}};
    const Mixture1 all = p3at::verifier::sum(x, y, 4);
    REQUIRE(all.components.size() == 4);
    CHECK(all.components[0] == Component1{0.125, 9.0, 1.5});
    CHECK(all.components[3] == Component1{0.375, 23.0, 5.0});
    for (std::size_t k : {std::size_t{1}, std::size_t{2}, std::size_t{3}}) {
      const Mixture1 reduced = p3at::verifier::sum(x, y, k);
      CHECK(reduced.components.size() == k);
      CHECK(reduced.mean() == doctest::Approx(x.mean() + y.mean()).epsilon(1e-13));
      CHECK(reduced.variance() == doctest::Approx(x.variance() + y.variance()).epsilon(1e-13));
    }
  }
  TEST_CASE("with an empty mixture is empty") {
    CHECK(p3at::verifier::sum(Mixture1{}, Mixture1::point(1.0), 4).components.empty());
  }
}

TEST_SUITE("maximum (Clark 1961)") {
  // The density of max(X, Y) is f_X F_Y + f_Y F_X.
  void check_clark(double m1, double v1, double m2, double v2) {
    const Mixture1 got = p3at::verifier::maximum(Mixture1::gaussian(m1, v1), Mixture1::gaussian(m2, v2), 4);
    REQUIRE(got.components.size() == 1);
    const auto density = [&](double z) {
      return gaussian_pdf(z, m1, v1) * gaussian_cdf(z, m2, v2) + gaussian_pdf(z, m2, v2) * gaussian_cdf(z, m1, v1);
    };
    const double spread = 12.0 * std::sqrt(std::max(v1, v2));
    const NumericMoments want = moments_of(density, std::min(m1, m2) - spread, std::max(m1, m2) + spread);
    CHECK(want.mass == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(got.mean() == doctest::Approx(want.mean).epsilon(1e-9));
    CHECK(got.variance() == doctest::Approx(want.var).epsilon(1e-8));
  }
  TEST_CASE("against numerical integration") {
    check_clark(0.0, 1.0, 0.0, 1.0);     // identical: mean 1/sqrt(pi), var 1 - 1/pi
    check_clark(1.0, 0.25, 0.0, 4.0);
    check_clark(5.0, 1.0, -2.0, 0.5);    // far apart: almost X
    check_clark(10.0, 2.0, 11.0, 0.01);  // a narrow and a wide one
    const Mixture1 iid = p3at::verifier::maximum(Mixture1::gaussian(0, 1), Mixture1::gaussian(0, 1), 1);
    CHECK(iid.mean() == doctest::Approx(1.0 / std::sqrt(std::numbers::pi)).epsilon(1e-14));
    CHECK(iid.variance() == doctest::Approx(1.0 - 1.0 / std::numbers::pi).epsilon(1e-14));
  }
  TEST_CASE("two point masses: the larger one") {
    const Mixture1 m = p3at::verifier::maximum(Mixture1::point(3.0), Mixture1::point(-1.0), 4);
    CHECK(m == Mixture1::point(3.0));
  }
  TEST_CASE("a Gaussian far below a point mass is the point mass; far above it, itself") {
    const Mixture1 low = p3at::verifier::maximum(Mixture1::gaussian(0.0, 1e-6), 5.0);
    CHECK(low.mean() == 5.0);
    CHECK(low.variance() == 0.0);
    const Mixture1 high = p3at::verifier::maximum(Mixture1::gaussian(5.0, 1e-6), 0.0);
    CHECK(high.mean() == doctest::Approx(5.0).epsilon(1e-15));
    CHECK(high.variance() == doctest::Approx(1e-6).epsilon(1e-12));
  }
  TEST_CASE("a subnormal spread far from the other side: finite, the dominant side's moments") {
    // A delivered message's residual max(D - R, 0), moment-matched event after
    // event, shrinks to a point at 0 with a subnormal variance (these are the
    // values tests/data/honest/meeting produced): against a cycle of 0.1 s the
    // standardised gap is -1e157, whose square overflowed and made the
    // variance inf * 0 = NaN.
    const Mixture1 residual = Mixture1::gaussian(3.78169e-314, 5.31754e-318);
    const Mixture1 seen = p3at::verifier::maximum(residual, 0.1);
    REQUIRE(seen.components.size() == 1);
    CHECK(seen.mean() == 0.1);
    CHECK(seen.variance() == 0.0);
    const Mixture1 both = p3at::verifier::maximum(residual, Mixture1::gaussian(0.1, 1e-300), 4);
    CHECK(both.mean() == 0.1);
    CHECK(both.variance() == 1e-300);
    // The other way round: the tiny one is the larger one by far.
    const Mixture1 above = p3at::verifier::maximum(Mixture1::gaussian(0.1, 5e-318), Mixture1::gaussian(0.0, 1e-320), 4);
    CHECK(above.mean() == 0.1);
    CHECK(std::isfinite(above.variance()));
    CHECK(above.variance() >= 0.0);
  }
  TEST_CASE("max with a constant against numerical integration: density f_X on (c, inf), mass F_X(c) at c") {
    const double m = 1.0;
    const double v = 2.0;
    const double c = 1.5;
    const Mixture1 got = p3at::verifier::maximum(Mixture1::gaussian(m, v), c);
    const double fc = gaussian_cdf(c, m, v);
    const double e1 = c * fc + integrate([&](double z) { return z * gaussian_pdf(z, m, v); }, c, m + 20.0);
    const double e2 = c * c * fc + integrate([&](double z) { return z * z * gaussian_pdf(z, m, v); }, c, m + 20.0);
    CHECK(got.mean() == doctest::Approx(e1).epsilon(1e-10));
    CHECK(got.variance() == doctest::Approx(e2 - e1 * e1).epsilon(1e-9));
  }
  TEST_CASE("of mixtures keeps the pairwise moments when the bound allows") {
    const Mixture1 x = two_components();
    const Mixture1 y = Mixture1::gaussian(1.0, 1.0);
    const Mixture1 m = p3at::verifier::maximum(x, y, 8);
    CHECK(m.components.size() == 2);
    // The whole mixture's moments against the density f_X F_Y + f_Y F_X.
    const auto density = [&](double z) {
      return x.cdf(z) * gaussian_pdf(z, 1.0, 1.0) +
             gaussian_cdf(z, 1.0, 1.0) * (0.25 * gaussian_pdf(z, -1.0, 0.5) + 0.75 * gaussian_pdf(z, 3.0, 2.0));
    };
    const NumericMoments want = moments_of(density, -20.0, 25.0);
    CHECK(m.mean() == doctest::Approx(want.mean).epsilon(1e-9));
    CHECK(m.variance() == doctest::Approx(want.var).epsilon(1e-8));
    // Reduced to one component, the same two moments.
    const Mixture1 one = p3at::verifier::maximum(x, y, 1);
    CHECK(one.components.size() == 1);
    CHECK(one.mean() == doctest::Approx(want.mean).epsilon(1e-9));
    CHECK(one.variance() == doctest::Approx(want.var).epsilon(1e-8));
  }
}

TEST_SUITE("probability_less") {
  TEST_CASE("of two Gaussians is Phi((my - mx) / sqrt(vx + vy))") {
    CHECK(p3at::verifier::probability_less(Mixture1::gaussian(1.0, 2.0), Mixture1::gaussian(2.0, 3.0)) ==
          doctest::Approx(normal_cdf(1.0 / std::sqrt(5.0))).epsilon(1e-15));
    CHECK(p3at::verifier::probability_less(Mixture1::gaussian(0.0, 1.0), Mixture1::gaussian(0.0, 1.0)) == 0.5);
  }
  TEST_CASE("of mixtures is the weighted sum over pairs, and P(X<Y) + P(Y<X) = 1 for continuous ones") {
    const Mixture1 x = two_components();
    const Mixture1 y{{Component1{0.4, 0.0, 1.0}, Component1{0.6, 4.0, 0.5}}};
    double want = 0.0;
    for (const Component1& a : x.components) {
      for (const Component1& b : y.components) {
        want += a.weight * b.weight * normal_cdf((b.mean - a.mean) / std::sqrt(a.var + b.var));
      }
    }
    const double p = p3at::verifier::probability_less(x, y);
    CHECK(p == doctest::Approx(want).epsilon(1e-15));
    CHECK(p + p3at::verifier::probability_less(y, x) == doctest::Approx(1.0).epsilon(1e-15));
  }
  TEST_CASE("point masses: strictly less; equal values are not less") {
    CHECK(p3at::verifier::probability_less(Mixture1::point(1.0), Mixture1::point(2.0)) == 1.0);
    CHECK(p3at::verifier::probability_less(Mixture1::point(2.0), Mixture1::point(1.0)) == 0.0);
    CHECK(p3at::verifier::probability_less(Mixture1::point(1.0), Mixture1::point(1.0)) == 0.0);
    CHECK(p3at::verifier::probability_less(Mixture1::point(1.0), Mixture1::gaussian(1.0, 4.0)) == 0.5);
  }
  TEST_CASE("an empty mixture gives 0") {
    CHECK(p3at::verifier::probability_less(Mixture1{}, Mixture1::point(1.0)) == 0.0);
  }
}

TEST_SUITE("conditioning on an ordering") {
  // X given X < Y has density f_X(x) (1 - F_Y(x)) / P(X < Y).
  void check_less(const Mixture1& x, double my, double vy, double lo, double hi, double tolerance) {
    double p = -1.0;
    const Mixture1 got = p3at::verifier::conditioned_less(x, Mixture1::gaussian(my, vy), 1, p);
    const auto density = [&](double z) {
      double fx = 0.0;
      for (const Component1& c : x.components) fx += c.weight * gaussian_pdf(z, c.mean, c.var);
      return fx * normal_cdf(-(z - my) / std::sqrt(vy));
    };
    const NumericMoments want = moments_of(density, lo, hi);
    CHECK(p == doctest::Approx(want.mass).epsilon(tolerance));
    CHECK(p == doctest::Approx(p3at::verifier::probability_less(x, Mixture1::gaussian(my, vy))).epsilon(1e-12));
    REQUIRE(got.components.size() == 1);  // bound 1: the moments are the whole conditioned mixture's
    CHECK(got.mean() == doctest::Approx(want.mean).epsilon(tolerance));
    CHECK(got.variance() == doctest::Approx(want.var).epsilon(tolerance));
  }
  TEST_CASE("X given X < Y against numerical integration") {
    check_less(Mixture1::gaussian(0.0, 1.0), 0.0, 1.0, -15.0, 15.0, 1e-9);
    check_less(Mixture1::gaussian(2.0, 0.5), 1.0, 3.0, -15.0, 15.0, 1e-9);
    check_less(Mixture1::gaussian(-3.0, 4.0), 5.0, 0.1, -30.0, 15.0, 1e-9);
    check_less(two_components(), 2.0, 1.0, -20.0, 20.0, 1e-9);
  }
  TEST_CASE("deep in the tail (phi/Phi from the Mills ratio's continued fraction)") {
    // D = X - Y ~ N(50, 2): P(X < Y) = Phi(-35.4), about 1e-274; X given it sits near -25.
    check_less(Mixture1::gaussian(0.0, 1.0), -50.0, 1.0, -35.0, -15.0, 1e-7);
  }
  TEST_CASE("X given X > Y against numerical integration") {
    const double my = 1.0;
    const double vy = 2.0;
    double p = -1.0;
    const Mixture1 x = Mixture1::gaussian(0.5, 1.5);
    const Mixture1 got = p3at::verifier::conditioned_greater(x, Mixture1::gaussian(my, vy), 4, p);
    const auto density = [&](double z) { return gaussian_pdf(z, 0.5, 1.5) * gaussian_cdf(z, my, vy); };
    const NumericMoments want = moments_of(density, -15.0, 15.0);
    CHECK(p == doctest::Approx(want.mass).epsilon(1e-10));
    CHECK(got.mean() == doctest::Approx(want.mean).epsilon(1e-9));
    CHECK(got.variance() == doctest::Approx(want.var).epsilon(1e-9));
    double p_less = -1.0;
    (void)p3at::verifier::conditioned_less(x, Mixture1::gaussian(my, vy), 4, p_less);
    CHECK(p + p_less == doctest::Approx(1.0).epsilon(1e-14));
  }
  TEST_CASE("a mixture on each side, no merging: each pair's component is kept") {
    double p = -1.0;
    const Mixture1 y{{Component1{0.5, 0.0, 1.0}, Component1{0.5, 2.0, 1.0}}};
    const Mixture1 got = p3at::verifier::conditioned_less(two_components(), y, 16, p);
    CHECK(got.components.size() == 4);
    double total = 0.0;
    for (const Component1& c : got.components) total += c.weight;
    CHECK(total == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(p == doctest::Approx(p3at::verifier::probability_less(two_components(), y)).epsilon(1e-14));
  }
  TEST_CASE("point masses, impossible orderings and empty input") {
    double p = -1.0;
    CHECK(p3at::verifier::conditioned_less(Mixture1::point(1.0), Mixture1::point(2.0), 4, p) == Mixture1::point(1.0));
    CHECK(p == 1.0);
    CHECK(p3at::verifier::conditioned_less(Mixture1::point(2.0), Mixture1::point(2.0), 4, p).components.empty());
    CHECK(p == 0.0);
    CHECK(p3at::verifier::conditioned_greater(Mixture1::point(2.0), Mixture1::point(2.0), 4, p).components.empty());
    CHECK(p == 0.0);
    p = -1.0;
    CHECK(p3at::verifier::conditioned_less(Mixture1{}, Mixture1::point(2.0), 4, p).components.empty());
    CHECK(p == 0.0);
    // A point mass against a Gaussian: the point, with the Gaussian's tail probability.
    const Mixture1 got = p3at::verifier::conditioned_greater(Mixture1::point(1.0), Mixture1::gaussian(0.0, 1.0), 4, p);
    CHECK(got == Mixture1::point(1.0));
    CHECK(p == doctest::Approx(normal_cdf(1.0)).epsilon(1e-15));
  }
}

TEST_SUITE("reduce") {
  // Ten components with spread-out weights, means and variances.
  Mixture1 ten() {
    Mixture1 x;
    for (int i = 0; i < 10; ++i) {
      x.components.push_back(Component1{1.0 + i % 3, 0.7 * i * i - 3.0 * i, 0.1 + 0.05 * (i % 4)});
    }
    x.normalise();
    return x;
  }
  TEST_CASE("respects the bound and keeps mean and variance") {
    const Mixture1 x = ten();
    for (std::size_t k = 1; k <= 10; ++k) {
      Mixture1 r = x;
      p3at::verifier::reduce(r, k);
      CHECK(r.components.size() == k);
      CHECK(r.mean() == doctest::Approx(x.mean()).epsilon(1e-13));
      CHECK(r.variance() == doctest::Approx(x.variance()).epsilon(1e-13));
      double total = 0.0;
      for (const Component1& c : r.components) total += c.weight;
      CHECK(total == doctest::Approx(1.0).epsilon(1e-15));
      CHECK(std::is_sorted(r.components.begin(), r.components.end(),
                           [](const Component1& a, const Component1& b) { return a.mean < b.mean; }));
    }
  }
  TEST_CASE("is deterministic: the same result, bit for bit, whatever the input order") {
    Mixture1 a = ten();
    Mixture1 b = ten();
    std::reverse(b.components.begin(), b.components.end());
    std::rotate(b.components.begin(), b.components.begin() + 3, b.components.end());
    p3at::verifier::reduce(a, 4);
    p3at::verifier::reduce(b, 4);
    CHECK(a == b);
  }
  TEST_CASE("merges the closest pair first: identical components before distinct ones") {
    Mixture1 x{{Component1{0.3, 0.0, 1.0}, Component1{0.3, 10.0, 1.0}, Component1{0.4, 10.0, 1.0}}};
    p3at::verifier::reduce(x, 2);
    REQUIRE(x.components.size() == 2);
    CHECK(x.components[0] == Component1{0.3, 0.0, 1.0});
    CHECK(x.components[1].mean == doctest::Approx(10.0).epsilon(1e-15));
    CHECK(x.components[1].var == doctest::Approx(1.0).epsilon(1e-15));
    // Two point masses at the same value merge before a point mass and a Gaussian.
    Mixture1 points{{Component1{0.25, 1.0, 0.0}, Component1{0.25, 1.0, 0.0}, Component1{0.5, 1.5, 1.0}}};
    p3at::verifier::reduce(points, 2);
    REQUIRE(points.components.size() == 2);
    CHECK(points.components[0] == Component1{0.5, 1.0, 0.0});
  }
  TEST_CASE("drops components below 1e-12 of the weight first") {
    Mixture1 x{{Component1{1.0, 0.0, 1.0}, Component1{1e-13, 100.0, 1.0}, Component1{1.0, 2.0, 1.0}}};
    p3at::verifier::reduce(x, 8);
    REQUIRE(x.components.size() == 2);
    CHECK(x.components[0].weight == 0.5);
    CHECK(x.components[1].mean == 2.0);
  }
  TEST_CASE("degenerate: empty stays empty, a bound of 0 means 1, no weight is no distribution") {
    Mixture1 empty;
    p3at::verifier::reduce(empty, 3);
    CHECK(empty.components.empty());
    Mixture1 x = ten();
    const double mean = x.mean();
    p3at::verifier::reduce(x, 0);
    CHECK(x.components.size() == 1);
    CHECK(x.components[0].mean == doctest::Approx(mean).epsilon(1e-13));
    Mixture1 zero{{Component1{0.0, 1.0, 1.0}}};
    p3at::verifier::reduce(zero, 3);
    CHECK(zero.components.empty());
  }
  TEST_CASE("merged point masses become a Gaussian with their spread") {
    Mixture1 x{{Component1{0.5, -1.0, 0.0}, Component1{0.5, 1.0, 0.0}}};
    p3at::verifier::reduce(x, 1);
    CHECK(x == Mixture1::gaussian(0.0, 1.0));
  }
}

TEST_SUITE("from_weighted_points") {
  const std::vector<double> kValues = {3.0, -1.0, 0.5, 2.0, 10.0, 11.0, -0.5};
  const std::vector<double> kWeights = {0.1, 0.2, 0.15, 0.1, 0.2, 0.05, 0.2};

  double weighted_mean() {
    double m = 0.0;
    for (std::size_t i = 0; i < kValues.size(); ++i) m += kWeights[i] * kValues[i];
    return m;
  }
  double weighted_var() {
    const double m = weighted_mean();
    double v = 0.0;
    for (std::size_t i = 0; i < kValues.size(); ++i) v += kWeights[i] * (kValues[i] - m) * (kValues[i] - m);
    return v;
  }

  TEST_CASE("keeps the points' mean and variance for every bound") {
    for (std::size_t k = 1; k <= 8; ++k) {
      const Mixture1 x = p3at::verifier::from_weighted_points(kValues, kWeights, k);
      CHECK(x.components.size() == std::min<std::size_t>(k, kValues.size()));
      CHECK(x.mean() == doctest::Approx(weighted_mean()).epsilon(1e-13));
      CHECK(x.variance() == doctest::Approx(weighted_var()).epsilon(1e-13));
    }
  }
  TEST_CASE("with room for every point, the points themselves (equal values as one)") {
    const Mixture1 x = p3at::verifier::from_weighted_points({2.0, 1.0, 2.0}, {1.0, 2.0, 1.0}, 5);
    CHECK(x == Mixture1{{Component1{0.5, 1.0, 0.0}, Component1{0.5, 2.0, 0.0}}});
  }
  TEST_CASE("groups are runs of neighbouring values: two clusters with a bound of 2") {
    const Mixture1 x = p3at::verifier::from_weighted_points(kValues, kWeights, 2);
    REQUIRE(x.components.size() == 2);
    // {-1, -0.5, 0.5, 2, 3} and {10, 11}.
    CHECK(x.components[0].weight == doctest::Approx(0.75).epsilon(1e-15));
    CHECK(x.components[1].weight == doctest::Approx(0.25).epsilon(1e-15));
    CHECK(x.components[1].mean == doctest::Approx((0.2 * 10.0 + 0.05 * 11.0) / 0.25).epsilon(1e-15));
  }
  TEST_CASE("bad input") {
    CHECK_THROWS_AS(p3at::verifier::from_weighted_points({1.0}, {1.0, 2.0}, 2), std::invalid_argument);
    CHECK_THROWS_AS(p3at::verifier::from_weighted_points({1.0}, {-1.0}, 2), std::invalid_argument);
    CHECK_THROWS_AS(p3at::verifier::from_weighted_points({std::numeric_limits<double>::quiet_NaN()}, {1.0}, 2), std::invalid_argument);
    CHECK(p3at::verifier::from_weighted_points({}, {}, 2).components.empty());
    CHECK(p3at::verifier::from_weighted_points({1.0}, {0.0}, 2).components.empty());
  }
}

TEST_SUITE("fit_em") {
  // Deterministic "samples": the mixture's quantiles at (i + 0.5) / n, by bisection on its CDF.
  std::vector<double> quantile_samples(const Mixture1& mixture, std::size_t n) {
    std::vector<double> out;
    for (std::size_t i = 0; i < n; ++i) {
      const double p = (static_cast<double>(i) + 0.5) / static_cast<double>(n);
      double lo = -100.0;
      double hi = 100.0;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (mixture.cdf(mid) < p ? lo : hi) = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    return out;
  }

  TEST_CASE("recovers a known two-component mixture") {
    const Mixture1 truth{{Component1{0.3, 0.0, 1.0}, Component1{0.7, 6.0, 0.25}}};
    const std::vector<double> samples = quantile_samples(truth, 4000);
    const Mixture1 fit = p3at::verifier::fit_em(samples, 2, 500);
    REQUIRE(fit.components.size() == 2);
    CHECK(fit.components[0].weight == doctest::Approx(0.3).epsilon(0.01));
    CHECK(fit.components[0].mean == doctest::Approx(0.0).scale(1.0).epsilon(0.01));
    CHECK(fit.components[0].var == doctest::Approx(1.0).epsilon(0.02));
    CHECK(fit.components[1].weight == doctest::Approx(0.7).epsilon(0.01));
    CHECK(fit.components[1].mean == doctest::Approx(6.0).epsilon(0.01));
    CHECK(fit.components[1].var == doctest::Approx(0.25).epsilon(0.02));
  }
  TEST_CASE("the same samples in another order give the same fit, bit for bit") {
    const Mixture1 truth{{Component1{0.5, 0.0, 1.0}, Component1{0.5, 4.0, 1.0}}};
    std::vector<double> samples = quantile_samples(truth, 300);
    const Mixture1 a = p3at::verifier::fit_em(samples, 3);
    std::reverse(samples.begin(), samples.end());
    std::rotate(samples.begin(), samples.begin() + 17, samples.end());
    CHECK(p3at::verifier::fit_em(samples, 3) == a);
  }
  TEST_CASE("one component is the samples' own mean and variance") {
    const std::vector<double> samples = {1.0, 2.0, 4.0, 7.0};
    const Mixture1 fit = p3at::verifier::fit_em(samples, 1);
    CHECK(fit == Mixture1::gaussian(3.5, (6.25 + 2.25 + 0.25 + 12.25) / 4.0));
    CHECK(p3at::verifier::fit_em(samples, 0) == fit);  // at least one component
  }
  TEST_CASE("degenerate samples") {
    CHECK(p3at::verifier::fit_em({}, 2).components.empty());
    CHECK(p3at::verifier::fit_em({3.0, 3.0, 3.0}, 2) == Mixture1::point(3.0));
    // More components than samples: at most one per sample, variances floored above 0.
    const Mixture1 two = p3at::verifier::fit_em({0.0, 10.0}, 5);
    REQUIRE(two.components.size() == 2);
    CHECK(two.components[0].mean == doctest::Approx(0.0).scale(1.0));
    CHECK(two.components[1].mean == doctest::Approx(10.0));
    CHECK(two.components[0].var > 0.0);
    CHECK_THROWS_AS(p3at::verifier::fit_em({1.0, std::numeric_limits<double>::infinity()}, 2), std::invalid_argument);
  }
}

TEST_SUITE("probability_within") {
  // P(|X| <= r) for X ~ N(mu, cov) by brute force in polar coordinates about the centre.
  // `angles` and `radii` must resolve the density's narrowest feature.
  double polar_integral(const Eigen::Vector2d& mu, const Eigen::Matrix2d& cov, double r, int angles = 256,
                        int radii = 800) {
    const Eigen::Matrix2d inv = cov.inverse();
    const double norm = 1.0 / (2.0 * std::numbers::pi * std::sqrt(cov.determinant()));
    return integrate(
        [&](double rho) {
          double ring = 0.0;  // the periodic trapezoid rule converges fast
          for (int k = 0; k < angles; ++k) {
            const double t = 2.0 * std::numbers::pi * k / angles;
            const Eigen::Vector2d d = Eigen::Vector2d(rho * std::cos(t), rho * std::sin(t)) - mu;
            ring += std::exp(-0.5 * d.dot(inv * d));
          }
          return ring * 2.0 * std::numbers::pi / angles * rho * norm;
        },
        0.0, r, radii);
  }

  TEST_CASE("centred isotropic: the Rayleigh CDF 1 - exp(-R^2 / 2 s^2)") {
    for (double sigma : {0.05, 0.5, 1.0, 3.0}) {
      for (double r : {0.1, 0.5, 1.0, 2.0, 4.0}) {
        const Gaussian2 x{Eigen::Vector2d(2.0, -1.0), Eigen::Matrix2d::Identity() * sigma * sigma};
        CHECK(p3at::verifier::probability_within(x, Eigen::Vector2d(2.0, -1.0), r) ==
              doctest::Approx(1.0 - std::exp(-r * r / (2.0 * sigma * sigma))).epsilon(1e-9).scale(1.0));
      }
    }
  }
  TEST_CASE("offset isotropic: 1 - Marcum Q1(d/s, R/s), the Rice CDF by numerical integration") {
    const double sigma = 0.7;
    for (double d : {0.3, 1.0, 2.5}) {
      for (double r : {0.5, 1.5, 3.0}) {
        const double rice = integrate(
            [&](double rho) {
              return rho / (sigma * sigma) * std::exp(-(rho * rho + d * d) / (2.0 * sigma * sigma)) *
                     std::cyl_bessel_i(0.0, rho * d / (sigma * sigma));
            },
            0.0, r);
        const Gaussian2 x{Eigen::Vector2d(d * 0.6, d * 0.8), Eigen::Matrix2d::Identity() * sigma * sigma};
        CHECK(p3at::verifier::probability_within(x, Eigen::Vector2d::Zero(), r) ==
              doctest::Approx(rice).epsilon(1e-8).scale(1.0));
      }
    }
  }
  TEST_CASE("anisotropic and rotated, against brute-force integration") {
    Eigen::Matrix2d cov;
    cov << 0.9, 0.5, 0.5, 0.4;
    for (const Eigen::Vector2d& mu : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.8, -0.3), Eigen::Vector2d(-1.5, 1.0)}) {
      for (double r : {0.3, 1.0, 2.0}) {
        const double want = polar_integral(mu, cov, r);
        CHECK(p3at::verifier::probability_within(Gaussian2{mu, cov}, Eigen::Vector2d::Zero(), r) ==
              doctest::Approx(want).epsilon(1e-8).scale(1.0));
      }
    }
    // Very elongated: sd 2 one way, 0.01 the other, its mean near the edge.
    Eigen::Matrix2d thin;
    thin << 4.0, 0.0, 0.0, 1e-4;
    const Eigen::Vector2d mu(0.5, 0.995);
    CHECK(p3at::verifier::probability_within(Gaussian2{mu, thin}, Eigen::Vector2d::Zero(), 1.0) ==
          doctest::Approx(polar_integral(mu, thin, 1.0, 1024, 4000)).epsilon(1e-6).scale(1.0));
  }
  TEST_CASE("far away and deep inside: 0 and 1 exactly") {
    const Gaussian2 x{Eigen::Vector2d(100.0, 0.0), Eigen::Matrix2d::Identity()};
    CHECK(p3at::verifier::probability_within(x, Eigen::Vector2d::Zero(), 5.0) == 0.0);
    CHECK(p3at::verifier::probability_within(x, Eigen::Vector2d(100.0, 1.0), 50.0) == 1.0);
  }
  TEST_CASE("degenerate covariances: a point, a line") {
    const Gaussian2 point{Eigen::Vector2d(3.0, 4.0), Eigen::Matrix2d::Zero()};
    CHECK(p3at::verifier::probability_within(point, Eigen::Vector2d::Zero(), 5.0) == 1.0);
    CHECK(p3at::verifier::probability_within(point, Eigen::Vector2d::Zero(), 4.999) == 0.0);
    CHECK(p3at::verifier::probability_within(point, Eigen::Vector2d(3.0, 4.0), 0.0) == 1.0);
    // All the spread along the diagonal: N(0, 1) along it, offset 0.6 across it.
    Eigen::Matrix2d line;
    line << 0.5, 0.5, 0.5, 0.5;
    const Eigen::Vector2d across = Eigen::Vector2d(-1.0, 1.0).normalized() * 0.6;
    const double chord = std::sqrt(1.0 - 0.36);
    CHECK(p3at::verifier::probability_within(Gaussian2{across, line}, Eigen::Vector2d::Zero(), 1.0) ==
          doctest::Approx(normal_cdf(chord) - normal_cdf(-chord)).epsilon(1e-14));
    CHECK(p3at::verifier::probability_within(Gaussian2{across * 2.0, line}, Eigen::Vector2d::Zero(), 1.0) == 0.0);
    // A radius of 0 holds nothing of a spread distribution; a negative one nothing at all.
    CHECK(p3at::verifier::probability_within(Gaussian2{across, line}, across, 0.0) == 0.0);
    CHECK(p3at::verifier::probability_within(point, Eigen::Vector2d(3.0, 4.0), -1.0) == 0.0);
  }
  TEST_CASE("a line by rounding (minor sd 1e-9 m): the line's chord, and an answer in bounded work") {
    // The CI gate's gen_8 produced this final-position component: its
    // determinant is rounding (minor variance 1.6e-18), so it is integrated
    // across a minor axis of 1.25e-9 m, where the quadrature's two rules
    // never agreed and halving to the depth limit took 20 s per radius.
    Eigen::Matrix2d cov;
    cov << 0.0082878725983382417, -0.014803638649515621, -0.014803638649515621, 0.026441974664206697;
    const Eigen::Vector2d mean(11.155092023003292, 5.3439331577409117);
    const Eigen::Vector2d goal(11.8, 3.1);
    // As a line: N(0, l1) along the major axis through the mean.
    const double a = cov(0, 0), c = cov(1, 1), b = cov(0, 1);
    const double l1 = 0.5 * (a + c) + std::hypot(0.5 * (a - c), b);
    const double angle = 0.5 * std::atan2(2.0 * b, a - c);
    const Eigen::Vector2d major(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d minor(-major.y(), major.x());
    const Eigen::Vector2d mu = mean - goal;
    for (const double r : {2.0, 2.1, 2.2, 2.3, 2.5}) {
      CAPTURE(r);
      const double across = mu.dot(minor);
      const double half_chord = std::sqrt(r * r - across * across);
      const double along = mu.dot(major);
      const double want = normal_cdf((half_chord - along) / std::sqrt(l1)) - normal_cdf((-half_chord - along) / std::sqrt(l1));
      int intervals = 0;
      CHECK(p3at::verifier::probability_within(Gaussian2{mean, cov}, goal, r, &intervals) ==
            doctest::Approx(want).epsilon(1e-7).scale(1.0));
      CHECK(intervals > 0);     // it did integrate (the line is not taken as one)
      CHECK(intervals <= 400);  // smooth work: a few per panel, not the depth limit's millions
    }
  }
  TEST_CASE("probability_apart: the difference of two positions, against the Rayleigh CDF") {
    const Gaussian2 a{Eigen::Vector2d(1.0, 1.0), Eigen::Matrix2d::Identity() * 0.3};
    const Gaussian2 b{Eigen::Vector2d(1.0, 1.0), Eigen::Matrix2d::Identity() * 0.2};
    // X - Y ~ N(0, 0.5 I): P(|X - Y| > d) = exp(-d^2 / (2 * 0.5)).
    for (double d : {0.1, 0.5, 1.0, 2.0}) {
      CHECK(p3at::verifier::probability_apart(a, b, d) == doctest::Approx(std::exp(-d * d)).epsilon(1e-9).scale(1.0));
    }
    CHECK(p3at::verifier::probability_apart(a, b, 0.0) == 1.0);
  }
  TEST_CASE("deterministic: the same inputs give the same bits") {
    Eigen::Matrix2d cov;
    cov << 0.3, -0.1, -0.1, 0.2;
    const Gaussian2 x{Eigen::Vector2d(0.4, 0.2), cov};
    CHECK(p3at::verifier::probability_within(x, Eigen::Vector2d::Zero(), 0.7) ==
          p3at::verifier::probability_within(x, Eigen::Vector2d::Zero(), 0.7));
  }
}
