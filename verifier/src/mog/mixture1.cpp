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
