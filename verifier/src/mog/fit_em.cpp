// Fitting a mixture to samples (calibration's delay and error data) by
// expectation-maximisation. Deterministic: the samples are sorted first and
// the components start on consecutive quantile groups, so the same samples
// in any order give the same mixture.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier {
namespace {

// A component's variance never falls below this share of the samples'
// variance: one component sitting on repeated values would otherwise shrink
// towards 0 and the likelihood grow without bound.
constexpr double kRelativeVarFloor = 1e-12;
// Stop when an iteration improves the log-likelihood by less than this share.
constexpr double kRelativeTolerance = 1e-10;

struct Moments {
  double mean = 0.0;
  double var = 0.0;
};

Moments moments(std::vector<double>::const_iterator first, std::vector<double>::const_iterator last) {
  const auto n = static_cast<double>(last - first);
  double sum = 0.0;
  for (auto it = first; it != last; ++it) sum += *it;
  const double mean = sum / n;
  double sq = 0.0;
  for (auto it = first; it != last; ++it) sq += (*it - mean) * (*it - mean);
  return Moments{mean, sq / n};
}

}  // namespace

Mixture1 fit_em(const std::vector<double>& samples, std::size_t k, std::size_t max_iterations) {
  if (samples.empty()) return {};
  for (double s : samples) {
    if (!std::isfinite(s)) throw std::invalid_argument("fit_em: samples must be finite");
  }
  std::vector<double> x = samples;
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  const std::size_t m = std::clamp<std::size_t>(k, 1, n);

  const Moments all = moments(x.begin(), x.end());
  if (!(all.var > 0.0)) return Mixture1::point(all.mean);  // every sample the same
  if (m == 1) return Mixture1::gaussian(all.mean, all.var);  // the maximum-likelihood Gaussian
  const double var_floor = kRelativeVarFloor * all.var;

  // Start: the sorted samples cut into m runs of (nearly) equal size.
  std::vector<double> weight(m);
  std::vector<double> mean(m);
  std::vector<double> var(m);
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t lo = j * n / m;
    const std::size_t hi = (j + 1) * n / m;
    const auto first = x.begin() + static_cast<std::ptrdiff_t>(lo);
    const auto last = x.begin() + static_cast<std::ptrdiff_t>(hi);
    const Moments g = moments(first, last);
    weight[j] = static_cast<double>(hi - lo) / static_cast<double>(n);
    mean[j] = g.mean;
    var[j] = std::max(g.var, var_floor);
  }

  std::vector<double> resp(n * m);  // responsibilities, sample-major
  std::vector<double> log_p(m);
  double previous_ll = 0.0;
  for (std::size_t iteration = 0; iteration < max_iterations; ++iteration) {
    // E step, with log-sum-exp so far-out samples do not underflow to 0/0.
    double ll = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double top = -std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < m; ++j) {
        if (weight[j] > 0.0) {
          const double d = x[i] - mean[j];
          log_p[j] = std::log(weight[j]) - 0.5 * std::log(2.0 * std::numbers::pi * var[j]) - 0.5 * d * d / var[j];
        } else {
          log_p[j] = -std::numeric_limits<double>::infinity();
        }
        top = std::max(top, log_p[j]);
      }
      double sum = 0.0;
      for (std::size_t j = 0; j < m; ++j) sum += std::exp(log_p[j] - top);
      const double lse = top + std::log(sum);
      ll += lse;
      for (std::size_t j = 0; j < m; ++j) resp[i * m + j] = std::exp(log_p[j] - lse);
    }
    if (iteration > 0 && std::abs(ll - previous_ll) <= kRelativeTolerance * std::max(std::abs(ll), 1.0)) break;
    previous_ll = ll;

    // M step. A component no sample belongs to keeps weight 0 and is dropped at the end.
    for (std::size_t j = 0; j < m; ++j) {
      double nj = 0.0;
      double sx = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        nj += resp[i * m + j];
        sx += resp[i * m + j] * x[i];
      }
      if (!(nj > 0.0)) {
        weight[j] = 0.0;
        continue;
      }
      const double mj = sx / nj;
      double sq = 0.0;
      for (std::size_t i = 0; i < n; ++i) sq += resp[i * m + j] * (x[i] - mj) * (x[i] - mj);
      weight[j] = nj / static_cast<double>(n);
      mean[j] = mj;
      var[j] = std::max(sq / nj, var_floor);
    }
  }

  Mixture1 out;
  for (std::size_t j = 0; j < m; ++j) out.components.push_back(Component1{weight[j], mean[j], var[j]});
  reduce(out, m);  // drops empty components, normalises, sorts by mean
  return out;
}

}  // namespace p3at::verifier
