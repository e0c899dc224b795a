// Arithmetic on independent random variables held as mixtures: sums, maxima,
// comparisons and conditioning on an ordering. Every operation works per
// component pair in closed form, then reduce() bounds the result's size.

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {
namespace {

// Beyond this many standard deviations below 0, phi/Phi is computed from the
// Mills ratio's continued fraction (Phi itself underflows near -37).
constexpr double kMillsSwitch = -30.0;
// Beyond this many standard deviations apart, the lower of two Gaussians
// never decides their maximum in double precision (Phi(-40) ~ 4e-350
// underflows to 0, and the mean's correction theta phi(40) is below any
// rounding of m): the maximum is the higher one, exactly. It must be taken
// as such rather than from the formula: a nearly-delivered message's
// residual max(D - R, 0) shrinks toward a point at 0 with a subnormal
// variance (5e-318 on tests/data/honest/meeting), and against a cycle of
// 0.1 s alpha is then -1e157, alpha^2 overflows to inf, and inf * P(= 0)
// made the variance NaN, which spread into every completion time.
constexpr double kMaxDominates = 40.0;

double total_weight(const Mixture1& x) {
  double total = 0.0;
  for (const Component1& c : x.components) total += c.weight;
  return total;
}

// phi(b) / Phi(b), the inverse Mills ratio, accurate for any b.
double inverse_mills(double b) {
  if (b >= kMillsSwitch) return normal_pdf(b) / normal_cdf(b);
  // Phi(-t) / phi(t) = 1 / (t + 1/(t + 2/(t + 3/(t + ...)))), evaluated from
  // the tail; for t > 30 fifty levels are far more than double precision needs.
  const double t = -b;
  double r = t;
  for (int k = 50; k >= 1; --k) r = t + static_cast<double>(k) / r;
  return r;
}

// Clark (1961): the exact mean and variance of max(X1, X2) for independent
// Gaussians, written about m2 with delta = m1 - m2 = alpha * theta so that no
// large squares cancel:
//   E   = m2 + theta (alpha P + f)
//   Var = v1 P + v2 Q + theta^2 (alpha^2 P Q + alpha f (Q - P) - f^2)
// with P = Phi(alpha), Q = Phi(-alpha), f = phi(alpha).
Component1 clark_max(double weight, double m1, double v1, double m2, double v2) {
  const double theta2 = v1 + v2;
  if (!(theta2 > 0.0)) return Component1{weight, std::max(m1, m2), 0.0};  // two point masses
  const double theta = std::sqrt(theta2);
  const double alpha = (m1 - m2) / theta;
  if (alpha > kMaxDominates) return Component1{weight, m1, v1};
  if (alpha < -kMaxDominates) return Component1{weight, m2, v2};
  const double p = normal_cdf(alpha);
  const double q = normal_cdf(-alpha);
  const double f = normal_pdf(alpha);
  const double mean = m2 + theta * (alpha * p + f);
  const double var = v1 * p + v2 * q + theta2 * (alpha * alpha * p * q + alpha * f * (q - p) - f * f);
  return Component1{weight, mean, std::max(var, 0.0)};
}

Mixture1 negated(const Mixture1& x) {
  Mixture1 out = x;
  for (Component1& c : out.components) c.mean = -c.mean;
  return out;
}

}  // namespace

Mixture1 sum(const Mixture1& x, const Mixture1& y, std::size_t max_components) {
  Mixture1 out;
  out.components.reserve(x.components.size() * y.components.size());
  for (const Component1& a : x.components) {
    for (const Component1& b : y.components) {
      out.components.push_back(Component1{a.weight * b.weight, a.mean + b.mean, a.var + b.var});
    }
  }
  reduce(out, max_components);
  return out;
}

Mixture1 maximum(const Mixture1& x, const Mixture1& y, std::size_t max_components) {
  Mixture1 out;
  out.components.reserve(x.components.size() * y.components.size());
  for (const Component1& a : x.components) {
    for (const Component1& b : y.components) {
      out.components.push_back(clark_max(a.weight * b.weight, a.mean, a.var, b.mean, b.var));
    }
  }
  reduce(out, max_components);
  return out;
}

Mixture1 maximum(const Mixture1& x, double c) {
  Mixture1 out;
  out.components.reserve(x.components.size());
  for (const Component1& a : x.components) out.components.push_back(clark_max(a.weight, a.mean, a.var, c, 0.0));
  return out;
}

double probability_less(const Mixture1& x, const Mixture1& y) {
  const double wx = total_weight(x);
  const double wy = total_weight(y);
  if (!(wx > 0.0) || !(wy > 0.0)) return 0.0;
  double p = 0.0;
  for (const Component1& a : x.components) {
    for (const Component1& b : y.components) {
      const double s2 = a.var + b.var;
      // Two point masses: X < Y strictly, so equal values are not "less".
      const double pij = s2 > 0.0 ? normal_cdf((b.mean - a.mean) / std::sqrt(s2)) : (a.mean < b.mean ? 1.0 : 0.0);
      p += a.weight * b.weight * pij;
    }
  }
  return std::clamp(p / (wx * wy), 0.0, 1.0);
}

// Per pair, with D = X - Y ~ N(mu, s2) and cov(X, D) = vx, X given D < 0 has
//   E   = mx - (vx / s) lambda
//   Var = vx - (vx^2 / s2) lambda (beta + lambda)
// where beta = -mu / s and lambda = phi(beta) / Phi(beta): the regression of X
// on D, with D's moments truncated above at 0.
Mixture1 conditioned_less(const Mixture1& x, const Mixture1& y, std::size_t max_components, double& probability) {
  probability = 0.0;
  const double wx = total_weight(x);
  const double wy = total_weight(y);
  if (!(wx > 0.0) || !(wy > 0.0)) return {};
  Mixture1 out;
  double total = 0.0;
  for (const Component1& a : x.components) {
    for (const Component1& b : y.components) {
      const double s2 = a.var + b.var;
      if (!(s2 > 0.0)) {
        if (a.mean < b.mean) {
          out.components.push_back(Component1{a.weight * b.weight, a.mean, 0.0});
          total += a.weight * b.weight;
        }
        continue;
      }
      const double s = std::sqrt(s2);
      const double beta = (b.mean - a.mean) / s;
      const double p = normal_cdf(beta);
      const double w = a.weight * b.weight * p;
      if (!(w > 0.0)) continue;
      const double lambda = inverse_mills(beta);
      const double mean = a.mean - (a.var / s) * lambda;
      const double var = a.var - (a.var * a.var / s2) * lambda * (beta + lambda);
      out.components.push_back(Component1{w, mean, std::max(var, 0.0)});
      total += w;
    }
  }
  probability = std::clamp(total / (wx * wy), 0.0, 1.0);
  if (!(total > 0.0)) return {};
  reduce(out, max_components);  // normalises
  return out;
}

Mixture1 conditioned_greater(const Mixture1& x, const Mixture1& y, std::size_t max_components,
                             double& probability) {
  // X > Y is -X < -Y.
  Mixture1 out = negated(conditioned_less(negated(x), negated(y), max_components, probability));
  reduce(out, max_components);  // back in increasing order of mean
  return out;
}

}  // namespace p3at::verifier
