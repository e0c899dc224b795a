// Choosing the cross-check grid (grid_choice.hpp).

#include "p3at/crosscheck/grid_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "p3at/common/number_format.hpp"

namespace p3at::crosscheck {

double round15(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  return std::strtod(format_general(x, 15).c_str(), nullptr);
}

std::string Axis::range() const {
  return format_general(first, 15) + ":" + format_general(last, 15) + ":" + format_general(step, 15);
}

Rise rise_of_curve(const std::vector<double>& axis, const std::vector<double>& p, double tail) {
  Rise r;
  if (axis.empty() || axis.size() != p.size()) return r;
  const auto [mn, mx] = std::minmax_element(p.begin(), p.end());
  if (*mx - *mn <= tail) return r;
  std::size_t lo = 0, hi = p.size() - 1;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p[i] <= *mn + tail) lo = i;
    else break;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p[i] >= *mx - tail) {
      hi = i;
      break;
    }
  }
  r.lo = axis[lo];
  r.hi = axis[std::max(lo, hi)];
  r.found = true;
  return r;
}

Rise rise_of_sample(std::vector<double> values, double tail) {
  Rise r;
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  if (values.empty()) return r;
  std::sort(values.begin(), values.end());
  const auto q = [&values](double f) {
    const std::size_t i = static_cast<std::size_t>(std::floor(f * static_cast<double>(values.size() - 1)));
    return values[std::min(i, values.size() - 1)];
  };
  r.lo = q(tail);
  r.hi = values[static_cast<std::size_t>(std::ceil((1.0 - tail) * static_cast<double>(values.size() - 1)))];
  r.found = true;
  return r;
}

Axis nice_axis(double lo, double hi, std::size_t count, double floor_value) {
  if (hi < lo) std::swap(lo, hi);
  double span = hi - lo;
  if (span < 1e-9 * std::max(1.0, std::abs(hi))) span = std::max(0.02 * std::abs(hi), 1e-3);
  lo -= 0.04 * span;
  hi += 0.04 * span;
  lo = std::max(lo, floor_value);
  if (hi <= lo) hi = lo + span;
  const double raw = (hi - lo) / static_cast<double>(std::max<std::size_t>(count, 2) - 1);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * decade;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (m * decade >= raw * (1 - 1e-12)) {
      step = m * decade;
      break;
    }
  }
  step = round15(step);
  Axis a;
  a.step = step;
  a.first = round15(std::max(std::floor(lo / step) * step, floor_value > 0 ? std::ceil(floor_value / step) * step : 0.0));
  const std::size_t n = static_cast<std::size_t>(std::ceil((hi - a.first) / step - 1e-9)) + 1;
  for (std::size_t k = 0; k < n; ++k) a.values.push_back(round15(a.first + static_cast<double>(k) * step));
  a.last = a.values.back();
  return a;
}

}  // namespace p3at::crosscheck
