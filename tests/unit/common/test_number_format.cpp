// format_fixed / format_general / format_scientific are printf's %*.*f, %.*g
// and %.*e byte for byte (the outputs they replaced were printf's), with no
// cut at any length; format_shortest reads back as the same double.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "p3at/common/number_format.hpp"

using namespace p3at;

namespace {

const std::vector<double> kValues = {0.0,    -0.0,     1.0,        -1.0,        0.1,   0.30000000000000004, 1.0 / 3.0,
                                     2.5,    -2.5,     1e-9,       123456.789,  1e21,  -1e300,              5e-324,
                                     0.0125, 1234.5678, 170.5,     std::nan(""), std::numeric_limits<double>::infinity()};

// printf itself, into a buffer larger than any of these values needs.
std::string printf_fixed(int width, int decimals, double v) {
  std::vector<char> buf(512);
  std::snprintf(buf.data(), buf.size(), "%*.*f", width, decimals, v);
  return buf.data();
}

std::string printf_general(int digits, double v) {
  std::vector<char> buf(512);
  std::snprintf(buf.data(), buf.size(), "%.*g", digits, v);
  return buf.data();
}

std::string printf_scientific(int decimals, double v) {
  std::vector<char> buf(512);
  std::snprintf(buf.data(), buf.size(), "%.*e", decimals, v);
  return buf.data();
}

}  // namespace

TEST_CASE("format_fixed is printf's %*.*f") {
  for (double v : kValues) {
    for (int decimals : {0, 1, 2, 3, 4, 6}) {
      CHECK(format_fixed(v, decimals) == printf_fixed(0, decimals, v));
      CHECK(format_fixed(v, decimals, 9) == printf_fixed(9, decimals, v));
    }
  }
  CHECK(format_fixed(2.5, 1, 6) == "   2.5");
  CHECK(format_fixed(-1e300, 3).size() == 306);  // never cut at a buffer's size
}

TEST_CASE("format_general is printf's %.*g; format_general(v) is %g") {
  for (double v : kValues) {
    for (int digits : {1, 6, 10, 12, 15, 17}) CHECK(format_general(v, digits) == printf_general(digits, v));
  }
  CHECK(format_general(0.1) == "0.1");
  CHECK(format_general(1.0 / 3.0) == "0.333333");
  CHECK(format_general(1.0 / 3.0, 17) == "0.33333333333333331");
}

TEST_CASE("format_scientific is printf's %.*e") {
  for (double v : kValues) CHECK(format_scientific(v, 2) == printf_scientific(2, v));
}

TEST_CASE("format_shortest reads back as the same double, in as few digits as that takes") {
  for (double v : kValues) {
    if (!std::isfinite(v)) continue;
    CHECK(std::strtod(format_shortest(v).c_str(), nullptr) == v);
  }
  CHECK(format_shortest(0.1) == "0.1");
  CHECK(format_shortest(0.30000000000000004) == "0.30000000000000004");
  CHECK(format_shortest(170.5) == "170.5");
  CHECK(format_shortest(1e21) == "1e+21");
}
