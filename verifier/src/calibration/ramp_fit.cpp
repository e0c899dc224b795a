#include "calibration/ramp_fit.hpp"

#include <cmath>
#include <functional>
#include <limits>

namespace p3at::verifier::calibration_detail {
namespace {

// A trace needs its rest (or cruise), its ramp and a little plateau (or rest).
constexpr std::size_t kMinRows = 4;
// The rate is searched within this factor of the speed-slope estimate, which
// is at most a few per cent off.
constexpr double kSearchFactor = 4.0;
// Grid points for a trace's start before refining it; the residual sum in the
// start has one minimum per grid cell at most for any ramp of two cycles or more.
constexpr int kStartGrid = 48;
constexpr int kGoldenIterations = 60;

// The minimum of f over [lo, hi] by golden-section search (f unimodal there).
double golden_min(const std::function<double(double)>& f, double lo, double hi, int iterations, double& at) {
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = lo;
  double b = hi;
  double x1 = b - g * (b - a);
  double x2 = a + g * (b - a);
  double f1 = f(x1);
  double f2 = f(x2);
  for (int i = 0; i < iterations; ++i) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    }
  }
  at = f1 <= f2 ? x1 : x2;
  return std::min(f1, f2);
}

// The residual sum of one trace for a rate and a start, its offset fitted (the mean residual).
double trace_ssr(const RampTrace& tr, double rate, double start) {
  double sum = 0.0;
  double sq = 0.0;
  for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
    const double r = tr.travel[i] - ramp_travel(tr.t_s[i] - start, rate, tr.plateau, tr.slowing);
    sum += r;
    sq += r * r;
  }
  return sq - sum * sum / static_cast<double>(tr.t_s.size());
}

// The trace's residual sum at its best start for this rate.
double best_over_start(const RampTrace& tr, double rate) {
  const double step = (tr.start_hi_s - tr.start_lo_s) / kStartGrid;
  double best = std::numeric_limits<double>::infinity();
  double best_at = tr.start_lo_s;
  for (int k = 0; k <= kStartGrid; ++k) {
    const double s = tr.start_lo_s + step * k;
    const double v = trace_ssr(tr, rate, s);
    if (v < best) {
      best = v;
      best_at = s;
    }
  }
  double at = best_at;
  const double refined = golden_min([&](double s) { return trace_ssr(tr, rate, s); }, best_at - step, best_at + step,
                                    kGoldenIterations, at);
  return std::min(best, refined);
}

}  // namespace

double ramp_travel(double u, double rate, double plateau, bool slowing) {
  const double ramp_s = plateau / rate;
  if (!slowing) {
    if (u <= 0.0) return 0.0;
    if (u < ramp_s) return 0.5 * rate * u * u;
    return 0.5 * plateau * ramp_s + plateau * (u - ramp_s);
  }
  if (u <= 0.0) return plateau * u;
  if (u < ramp_s) return plateau * u - 0.5 * rate * u * u;
  return 0.5 * plateau * ramp_s;
}

RampFit fit_ramp_rate(const std::vector<RampTrace>& traces, double initial) {
  RampFit out;
  std::vector<const RampTrace*> used;
  std::size_t points = 0;
  for (const RampTrace& tr : traces) {
    if (tr.t_s.size() < kMinRows || tr.t_s.size() != tr.travel.size() || !(tr.plateau > 0.0) ||
        !(tr.start_hi_s > tr.start_lo_s)) {
      continue;
    }
    used.push_back(&tr);
    points += tr.t_s.size();
  }
  if (used.size() < 2 || !(initial > 0.0)) return out;

  const auto total = [&](double rate) {
    double s = 0.0;
    for (const RampTrace* tr : used) s += best_over_start(*tr, rate);
    return s;
  };
  // Searched on log(rate): the bracket is a factor either side.
  const double lo = std::log(initial / kSearchFactor);
  const double hi = std::log(initial * kSearchFactor);
  double at = 0.0;
  const double ssr = golden_min([&](double x) { return total(std::exp(x)); }, lo, hi, kGoldenIterations, at);
  if (at - lo < 1e-3 || hi - at < 1e-3) return out;
  const double rate = std::exp(at);

  // Standard error from the residual sum's curvature in the rate (the
  // profile over the starts and offsets): var = 2 sigma^2 / S''.
  const double h = 0.01 * rate;
  const double curvature = (total(rate + h) - 2.0 * ssr + total(rate - h)) / (h * h);
  const std::size_t params = 1 + 2 * used.size();
  const double sigma2 = ssr / static_cast<double>(points > params ? points - params : 1);
  out.rate = rate;
  out.se = curvature > 0.0 ? std::sqrt(2.0 * sigma2 / curvature) : 0.0;
  out.rms = std::sqrt(ssr / static_cast<double>(points));
  out.ramps = used.size();
  out.ok = true;
  return out;
}

}  // namespace p3at::verifier::calibration_detail
