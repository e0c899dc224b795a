// The 1-D mixture's own members and the standard normal helpers.

#include <cmath>
#include <limits>
#include <numbers>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {

double normal_cdf(double z) {
  // erfc keeps full relative accuracy in the lower tail, where 1 - erf would
  // cancel to 0; the upper tail is 1 - (a small number), exact enough there.
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

double normal_quantile(double p) {
  if (std::isnan(p)) return p;
  if (p <= 0.0) return -std::numeric_limits<double>::infinity();
  if (p >= 1.0) return std::numeric_limits<double>::infinity();
  // The lower tail's own side (normal_cdf is accurate there), mirrored for
  // p > 1/2. Start from Abramowitz and Stegun 26.2.23 (error below 4.5e-4)
  // and polish with Newton steps on normal_cdf, which converge quadratically
  // from there.
  const double q = std::min(p, 1.0 - p);
  const double t = std::sqrt(-2.0 * std::log(q));
  double z = -(t - (2.515517 + 0.802853 * t + 0.010328 * t * t) / (1.0 + 1.432788 * t + 0.189269 * t * t + 0.001308 * t * t * t));
  for (int i = 0; i < 4; ++i) {
    const double density = normal_pdf(z);
    if (!(density > 0.0)) break;
    z -= (normal_cdf(z) - q) / density;
  }
  return p < 0.5 ? z : -z;
}

Mixture1 Mixture1::point(double value) { return Mixture1{{Component1{1.0, value, 0.0}}}; }

Mixture1 Mixture1::gaussian(double mean, double var) { return Mixture1{{Component1{1.0, mean, var}}}; }

namespace {

double total_weight(const Mixture1& x) {
  double total = 0.0;
  for (const Component1& c : x.components) total += c.weight;
  return total;
}

}  // namespace

double Mixture1::mean() const {
  const double total = total_weight(*this);
  if (components.empty() || total <= 0.0) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const Component1& c : components) sum += c.weight * c.mean;
  return sum / total;
}

double Mixture1::variance() const {
  const double total = total_weight(*this);
  if (components.empty() || total <= 0.0) return std::numeric_limits<double>::quiet_NaN();
  // Spread about the overall mean, not E[X^2] - E[X]^2, which cancels badly
  // for narrow mixtures far from 0 (times of a few hundred seconds).
  const double m = mean();
  double sum = 0.0;
  for (const Component1& c : components) {
    const double d = c.mean - m;
    sum += c.weight * (c.var + d * d);
  }
  return sum / total;
}

double Mixture1::cdf(double x) const {
  const double total = total_weight(*this);
  if (components.empty() || total <= 0.0) return 0.0;
  double sum = 0.0;
  for (const Component1& c : components) {
    if (c.var <= 0.0) {
      sum += x >= c.mean ? c.weight : 0.0;
    } else {
      sum += c.weight * normal_cdf((x - c.mean) / std::sqrt(c.var));
    }
  }
  return sum / total;
}

void Mixture1::normalise() {
  const double total = total_weight(*this);
  if (components.empty() || !(total > 0.0)) return;
  for (Component1& c : components) c.weight /= total;
}

Mixture1 shifted(const Mixture1& x, double c) {
  Mixture1 out = x;
  for (Component1& component : out.components) component.mean += c;
  return out;
}

}  // namespace p3at::verifier
