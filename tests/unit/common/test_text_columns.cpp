// left_aligned / right_aligned are printf's %-*s and %*s byte for byte, and
// keep a text longer than its column whole.
#include <doctest/doctest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "p3at/common/text_columns.hpp"

using namespace p3at;

namespace {

std::string printf_left(int width, const std::string& text) {
  std::vector<char> buf(4096);
  std::snprintf(buf.data(), buf.size(), "%-*s", width, text.c_str());
  return buf.data();
}

std::string printf_right(int width, const std::string& text) {
  std::vector<char> buf(4096);
  std::snprintf(buf.data(), buf.size(), "%*s", width, text.c_str());
  return buf.data();
}

}  // namespace

TEST_CASE("columns are printf's %-*s and %*s, and never cut") {
  const std::string long_text(600, 'x');
  for (const std::string& text : {std::string(), std::string("gen_7"), std::string("time curve, 1 % shift"),
                                  std::string("exactly18charsXXXX"), long_text}) {
    for (int width : {0, 5, 18, 26, 52}) {
      CAPTURE(text);
      CAPTURE(width);
      CHECK(left_aligned(text, static_cast<std::size_t>(width)) == printf_left(width, text));
      CHECK(right_aligned(text, static_cast<std::size_t>(width)) == printf_right(width, text));
    }
  }
  CHECK(left_aligned(long_text, 18).size() == 600);
  CHECK(right_aligned("7", 5) == "    7");
}
