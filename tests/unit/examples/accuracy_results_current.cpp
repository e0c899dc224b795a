// docs/results holds the evidence that verify agrees with validation on the
// shipped examples: for each, `vipars verify` and a 10,000-run `vipars
// validate` on one grid, and the report made from the two. Those documents
// are numbers in docs/, so they must be what today's code measures. They went
// stale once for three days: validation began recording runs at rest (26
// November) and nobody remade them, and the docs then blamed the verifier for
// a 0.0985 error that was 0.057 against current runs.
//
// This remakes both documents of each example with the built vipars, by the
// commands of docs/results/README.md, and requires the stored grids to match:
// the validation exactly (seeded runs: the same counts), the verification to
// 1e-9. When it fails, remake docs/results with those commands and update the
// figures the README quotes. About 50 s of validation on two cores, so label
// `accuracy` (release stage only).
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

struct Example {
  const char* name;
  const char* tmax_range;
  const char* rmax_range;
};

// The grids of docs/results/README.md's commands.
const std::vector<Example> kExamples{
    {"bounding_overwatch", "170:230:1", "1:3:0.05"},
    {"three_robots", "150:185:0.5", "0.5:1.3:0.01"},
    {"concurrent_moves", "105:165:0.5", "0.7:1.3:0.01"},
};

std::string source(const std::string& path) { return std::string(P3AT_SOURCE_DIR) + "/" + path; }

nlohmann::json stored(const std::string& example, const std::string& document) {
  const std::string text = p3at::test::read_file(source("docs/results/" + example + "/" + document));
  REQUIRE_MESSAGE(!text.empty(), "docs/results/" << example << "/" << document << " is missing");
  return nlohmann::json::parse(text);
}

nlohmann::json fresh(const std::string& command) {
  const auto r = p3at::test::run_command(p3at::test::vipars_binary() + " " + command);
  INFO(command << "\nstderr: " << r.err);
  REQUIRE((r.status == 0 || r.status == 1));  // GO or NO-GO: both print the document
  return nlohmann::json::parse(r.out);
}

/// The largest difference between the two documents' grids, over every
/// probability array they share.
double grid_difference(const nlohmann::json& a, const nlohmann::json& b) {
  double worst = 0.0;
  for (const char* key : {"p_time", "p_radius", "p_joint"}) {
    const auto& x = a.at("grid").at(key);
    const auto& y = b.at("grid").at(key);
    REQUIRE(x.size() == y.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i].is_array()) {
        REQUIRE(x[i].size() == y[i].size());
        for (std::size_t j = 0; j < x[i].size(); ++j) {
          worst = std::max(worst, std::abs(x[i][j].get<double>() - y[i][j].get<double>()));
        }
      } else {
        worst = std::max(worst, std::abs(x[i].get<double>() - y[i].get<double>()));
      }
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("docs/results: the stored verifications and validations are what the code measures today") {
  for (const Example& e : kExamples) {
    const std::string name = e.name;
    INFO(name << ": remake docs/results/" << name << " with the commands in docs/results/README.md");
    const std::string mission = source("examples/" + name + "/mission.yaml");
    const std::string grid = std::string(" --tmax-range ") + e.tmax_range + " --rmax-range " + e.rmax_range + " --json";
    const nlohmann::json verify =
        fresh("verify " + mission + " --models " + source("examples/" + name + "/models.yaml") + grid);
    CHECK(grid_difference(verify, stored(name, "verify.json")) < 1e-9);
    const nlohmann::json validate = fresh("validate " + mission + " --world " +
                                          source("examples/" + name + "/world.yaml") +
                                          " --trials 10000 --jobs 2 --seed 1" + grid);
    CHECK(grid_difference(validate, stored(name, "validate.json")) == 0.0);
  }
}
