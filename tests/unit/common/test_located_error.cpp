// One located error for every reader of input files.
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "p3at/common/located_error.hpp"

using p3at::LocatedError;

TEST_CASE("what() is file:line:column: detail, or file: detail without a position") {
  const LocatedError e("m.yaml", 3, 14, "expected a number");
  CHECK(std::string(e.what()) == "m.yaml:3:14: expected a number");
  CHECK(e.file() == "m.yaml");
  CHECK(e.line() == 3);
  CHECK(e.column() == 14);
  CHECK(e.detail() == "expected a number");
  CHECK(std::string(LocatedError("m.yaml", 0, 0, "cannot read").what()) == "m.yaml: cannot read");
}

TEST_CASE("a reader's own error is a LocatedError and a std::runtime_error") {
  struct ReaderError : LocatedError {
    using LocatedError::LocatedError;
  };
  try {
    throw ReaderError("c.pars", 1, 2, "unexpected ')'");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) == "c.pars:1:2: unexpected ')'");
  }
}
