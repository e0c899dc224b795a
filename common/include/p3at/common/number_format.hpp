#pragma once
/// The project's one way of writing a double as text, in the three forms its
/// outputs use (CSV, JSON-adjacent text, logs, figures, messages):
///   format_fixed(v, 3)        printf's %.3f (with a width: %*.*f)
///   format_general(v, 6)      printf's %.6g (%g is format_general(v))
///   format_scientific(v, 2)   printf's %.2e
///   format_shortest(v)        the shortest decimal that reads back as the
///                             same double (std::to_chars)
/// Never truncated, whatever the magnitude.

#include <charconv>
#include <cstddef>
#include <cstdio>
#include <string>
#include <system_error>

namespace p3at {

namespace number_format_detail {
// `print(buffer, size)` is one snprintf call (its format a literal, so the
// compiler checks it); run again into a buffer of the right size when 64
// characters were not enough.
template <class Print>
std::string printed(Print print) {
  char buffer[64];
  const int n = print(buffer, sizeof buffer);
  if (n < 0) return {};
  const auto size = static_cast<std::size_t>(n);
  if (size < sizeof buffer) return std::string(buffer, size);
  std::string out(size + 1, '\0');
  print(out.data(), out.size());
  out.resize(size);
  return out;
}
}  // namespace number_format_detail

/// printf("%*.*f", width, decimals, value).
inline std::string format_fixed(double value, int decimals, int width = 0) {
  return number_format_detail::printed(
      [&](char* buffer, std::size_t size) { return std::snprintf(buffer, size, "%*.*f", width, decimals, value); });
}

/// printf("%.*g", significant, value); format_general(v) is printf("%g", v).
inline std::string format_general(double value, int significant = 6) {
  return number_format_detail::printed(
      [&](char* buffer, std::size_t size) { return std::snprintf(buffer, size, "%.*g", significant, value); });
}

/// printf("%.*e", decimals, value).
inline std::string format_scientific(double value, int decimals) {
  return number_format_detail::printed(
      [&](char* buffer, std::size_t size) { return std::snprintf(buffer, size, "%.*e", decimals, value); });
}

/// The shortest decimal that reads back as the same double.
inline std::string format_shortest(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (ec != std::errc()) return "nan";  // not reachable: any double fits in 64 characters
  return std::string(buffer, end);
}

}  // namespace p3at
