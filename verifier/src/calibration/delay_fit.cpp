// The team link's delays as mixtures of Gaussians: fit_em() for 1, 2, ...
// components, the number chosen by the Bayesian information criterion (a
// component must earn its three parameters), and the Kolmogorov-Smirnov
// distance between the samples and the chosen mixture as the fit's quality.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "p3at/verifier/calibration.hpp"
#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {
namespace {

double log_likelihood(const Mixture1& mixture, const std::vector<double>& samples) {
  double ll = 0.0;
  for (double x : samples) {
    double p = 0.0;
    for (const Component1& c : mixture.components) {
      if (c.var > 0.0) {
        const double z = (x - c.mean) / std::sqrt(c.var);
        p += c.weight * std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi * c.var);
      }
    }
    ll += std::log(std::max(p, std::numeric_limits<double>::min()));
  }
  return ll;
}

double ks_distance(const Mixture1& mixture, std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  const auto n = static_cast<double>(samples.size());
  double d = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double f = mixture.cdf(samples[i]);
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  return d;
}

}  // namespace

DelayCalibration fit_delay(const std::vector<double>& samples_s, std::size_t lost, std::size_t max_components) {
  DelayCalibration out;
  out.samples = samples_s.size();
  out.lost = lost;
  if (samples_s.empty()) return out;
  const bool all_equal = std::all_of(samples_s.begin(), samples_s.end(), [&](double s) { return s == samples_s.front(); });
  if (all_equal) {
    out.mixture = Mixture1::point(samples_s.front());
    return out;
  }
  const auto n = static_cast<double>(samples_s.size());
  double best = HUGE_VAL;
  // Each component needs a few samples of its own to be worth fitting.
  const std::size_t k_max = std::clamp<std::size_t>(samples_s.size() / 5, 1, std::max<std::size_t>(max_components, 1));
  for (std::size_t k = 1; k <= k_max; ++k) {
    const Mixture1 m = fit_em(samples_s, k);
    const auto parameters = static_cast<double>(3 * m.components.size() - 1);
    const double bic = -2.0 * log_likelihood(m, samples_s) + parameters * std::log(n);
    out.bic.push_back(bic);
    if (bic < best) {
      best = bic;
      out.mixture = m;
    }
  }
  out.ks_distance = ks_distance(out.mixture, samples_s);
  return out;
}

}  // namespace p3at::verifier
