// `vipars verify` as an operator runs it (the built binary, beside this test
// in <build>/bin): GO exits 0, NO-GO 1, bad input 2, and --json carries the
// documented keys with the same numbers as the library call.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

using Run = p3at::test::CommandOutcome;

std::string vipars() { return p3at::test::vipars_binary(); }

std::string example(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/" + name;
}

// vipars with `args`; its stdout (stderr is captured apart and not looked at).
Run run(const std::string& args) { return p3at::test::run_command(vipars() + " " + args); }

}  // namespace

TEST_CASE("vipars verify: exit 1 for NO-GO, 0 for GO, 2 for bad input") {
  const std::string mission = example("mission.yaml");
  const std::string models = example("models.yaml");
  // The example's own criteria (200 s, 2.0 m, threshold 0.8) are not met: the
  // robots end about 1.9 m from their goals.
  const Run no_go = run("verify " + mission + " --models " + models);
  CHECK(no_go.status == 1);
  CHECK(no_go.out.find("decision: NO-GO") != std::string::npos);
  CHECK(no_go.out.find("threshold") != std::string::npos);
  // Looser criteria are met.
  const Run go = run("verify " + mission + " --models " + models + " --tmax 230 --rmax 3.0");
  CHECK(go.status == 0);
  CHECK(go.out.find("decision: GO") != std::string::npos);
  // Bad input: a missing models file, a malformed range, a non-number.
  CHECK(run("verify " + mission + " --models /nonexistent/models.yaml").status == 2);
  CHECK(run("verify " + mission + " --models " + models + " --tmax-range 200:100:5").status == 2);
  CHECK(run("verify " + mission + " --models " + models + " --tmax abc").status == 2);
  CHECK(run("verify /nonexistent/mission.yaml --models " + models).status == 2);
}

TEST_CASE("vipars verify --json: the documented keys and a grid of the right shape") {
  const Run r = run("verify " + example("mission.yaml") + " --models " + example("models.yaml") +
                    " --tmax-range 180:220:10 --rmax-range 1:3:0.5 --json");
  CHECK(r.status == 1);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j.at("decision") == "no-go");
  for (const char* key : {"p_time", "p_radius", "p_joint", "tmax_s", "rmax_m", "threshold"}) {
    CHECK(j.at(key).is_number());
  }
  CHECK(j.at("p_joint").get<double>() <= j.at("p_time").get<double>());
  const nlohmann::json& g = j.at("grid");
  REQUIRE(g.at("tmax").size() == 5);
  REQUIRE(g.at("rmax").size() == 5);
  CHECK(g.at("p_time").size() == 5);
  CHECK(g.at("p_radius").size() == 5);
  REQUIRE(g.at("p_joint").size() == 5);
  REQUIRE(g.at("region").size() == 5);
  for (std::size_t i = 0; i < 5; ++i) {
    CHECK(g.at("p_joint")[i].size() == 5);
    CHECK(g.at("region")[i].size() == 5);
  }
  // Deterministic: the same command prints the same bytes.
  const Run again = run("verify " + example("mission.yaml") + " --models " + example("models.yaml") +
                        " --tmax-range 180:220:10 --rmax-range 1:3:0.5 --json");
  CHECK(again.out == r.out);
}
