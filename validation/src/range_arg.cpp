#include "p3at/validation/range_arg.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace p3at::vipars {
namespace {

constexpr double kIntegralTolerance = 1e-9;

Error range_error(std::string_view text, const std::string& what) {
  return make_error(Error::Code::invalid_argument,
                    "expected A:B:STEP" + what + ", got '" + std::string(text) + "'");
}

// A whole field must be one finite decimal number (std::from_chars: no
// locale, no leading '+' or spaces, nothing left over).
bool parse_number(std::string_view field, double& value) {
  if (field.empty()) return false;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

// Nearest double to the value's 15-significant-digit decimal: undoes the
// last-bit rounding of A + k·STEP (1.7000000000000002 -> 1.7) without
// changing any value a person could have meant.
double tidy(double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", value);
  return std::strtod(buf, nullptr);
}

}  // namespace

Result<std::vector<double>> parse_range(std::string_view text) {
  const std::size_t first = text.find(':');
  const std::size_t second = first == std::string_view::npos ? first : text.find(':', first + 1);
  if (second == std::string_view::npos || text.find(':', second + 1) != std::string_view::npos) {
    return range_error(text, " (three numbers separated by ':')");
  }
  double a = 0.0, b = 0.0, step = 0.0;
  if (!parse_number(text.substr(0, first), a)) return range_error(text, " with A a finite number");
  if (!parse_number(text.substr(first + 1, second - first - 1), b)) {
    return range_error(text, " with B a finite number");
  }
  if (!parse_number(text.substr(second + 1), step)) return range_error(text, " with STEP a finite number");
  if (!(step > 0.0)) return range_error(text, " with STEP > 0");
  if (b < a) return range_error(text, " with B >= A");

  const double steps = (b - a) / step;
  if (!(steps < static_cast<double>(kMaxRangeValues))) {
    return range_error(text, " with at most " + std::to_string(kMaxRangeValues) + " values");
  }
  const double nearest = std::round(steps);
  const bool ends_on_b = std::fabs(steps - nearest) <= kIntegralTolerance;
  const auto last = static_cast<std::size_t>(ends_on_b ? nearest : std::floor(steps));
  if (last + 1 > kMaxRangeValues) {
    return range_error(text, " with at most " + std::to_string(kMaxRangeValues) + " values");
  }
  std::vector<double> values;
  values.reserve(last + 1);
  for (std::size_t k = 0; k <= last; ++k) values.push_back(tidy(a + static_cast<double>(k) * step));
  values.front() = a;
  if (ends_on_b) values.back() = b;
  return values;
}

}  // namespace p3at::vipars
