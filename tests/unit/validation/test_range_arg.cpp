// The A:B:STEP axis parser shared by `vipars validate` and `vipars verify`.

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "p3at/validation/range_arg.hpp"

using p3at::vipars::parse_range;

TEST_CASE("A:B:STEP includes B when it falls on a step") {
  const auto t = parse_range("170:230:2");
  REQUIRE(t.ok());
  REQUIRE(t->size() == 31);
  CHECK(t->front() == 170.0);
  CHECK(t->at(1) == 172.0);
  CHECK(t->back() == 230.0);

  // 0.1 is not exact in binary: (3 - 1) / 0.1 is 20 only within rounding.
  const auto r = parse_range("1:3:0.1");
  REQUIRE(r.ok());
  REQUIRE(r->size() == 21);
  CHECK(r->front() == 1.0);
  CHECK(r->at(7) == 1.7);  // tidied: not 1.7000000000000002
  CHECK(r->at(3) == 1.3);
  CHECK(r->back() == 3.0);
  for (std::size_t i = 1; i < r->size(); ++i) CHECK(r->at(i) > r->at(i - 1));

  const auto q = parse_range("0:0.3:0.1");
  REQUIRE(q.ok());
  CHECK(*q == std::vector<double>{0.0, 0.1, 0.2, 0.3});
}

TEST_CASE("A:B:STEP stops before B when B is between steps") {
  const auto r = parse_range("1:2:0.3");
  REQUIRE(r.ok());
  CHECK(*r == std::vector<double>{1.0, 1.3, 1.6, 1.9});
  const auto s = parse_range("0:10:4");
  REQUIRE(s.ok());
  CHECK(*s == std::vector<double>{0.0, 4.0, 8.0});
}

TEST_CASE("A:A:STEP is one value; negatives and exponents parse") {
  const auto one = parse_range("200:200:5");
  REQUIRE(one.ok());
  CHECK(*one == std::vector<double>{200.0});
  const auto neg = parse_range("-1:1:1");
  REQUIRE(neg.ok());
  CHECK(*neg == std::vector<double>{-1.0, 0.0, 1.0});
  const auto exp = parse_range("1e2:3e2:1e2");
  REQUIRE(exp.ok());
  CHECK(*exp == std::vector<double>{100.0, 200.0, 300.0});
}

TEST_CASE("bad ranges are refused with what was expected") {
  const auto error_of = [](const char* text) {
    const auto r = parse_range(text);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == p3at::Error::Code::invalid_argument);
    return r.error().message;
  };
  CHECK(error_of("") == "expected A:B:STEP (three numbers separated by ':'), got ''");
  CHECK(error_of("170:230") == "expected A:B:STEP (three numbers separated by ':'), got '170:230'");
  CHECK(error_of("1:2:3:4") == "expected A:B:STEP (three numbers separated by ':'), got '1:2:3:4'");
  CHECK(error_of("a:230:2") == "expected A:B:STEP with A a finite number, got 'a:230:2'");
  CHECK(error_of("170::2") == "expected A:B:STEP with B a finite number, got '170::2'");
  CHECK(error_of("170:230:") == "expected A:B:STEP with STEP a finite number, got '170:230:'");
  CHECK(error_of("170:230:2s") == "expected A:B:STEP with STEP a finite number, got '170:230:2s'");
  CHECK(error_of(" 170:230:2") == "expected A:B:STEP with A a finite number, got ' 170:230:2'");
  CHECK(error_of("inf:230:2") == "expected A:B:STEP with A a finite number, got 'inf:230:2'");
  CHECK(error_of("nan:230:2") == "expected A:B:STEP with A a finite number, got 'nan:230:2'");
  CHECK(error_of("1:3:0") == "expected A:B:STEP with STEP > 0, got '1:3:0'");
  CHECK(error_of("1:3:-0.1") == "expected A:B:STEP with STEP > 0, got '1:3:-0.1'");
  CHECK(error_of("3:1:0.1") == "expected A:B:STEP with B >= A, got '3:1:0.1'");
  CHECK(error_of("0:1:1e-9") == "expected A:B:STEP with at most 100000 values, got '0:1:1e-9'");
  CHECK(error_of("0:1e300:1e-300") == "expected A:B:STEP with at most 100000 values, got '0:1e300:1e-300'");
}

TEST_CASE("the largest allowed axis") {
  const auto r = parse_range("0:99999:1");
  REQUIRE(r.ok());
  CHECK(r->size() == 100000);
  CHECK_FALSE(parse_range("0:100000:1").ok());
}
