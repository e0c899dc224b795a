#pragma once
// A command line's stdout read as JSON, for the CLI tests that compare
// `vipars verify --json` with `vipars validate --json`: the command must
// print something, and what it prints must parse (doctest fails the test
// case otherwise).

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

namespace p3at::test {

inline nlohmann::json run_json(const std::string& command) {
  const auto r = run_command(command);
  REQUIRE(!r.out.empty());
  return nlohmann::json::parse(r.out);
}

}  // namespace p3at::test
