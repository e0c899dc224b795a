// The gate's decision point has floors (docs/verifier.md, "The decision"): it
// decides 1 % stricter than the operator's Tmax and Rmax, but at least one
// control cycle and one step (max_speed_mps x cycle_s) stricter. Why, on a
// real generated mission (tests/data/decision_floor, the fresh sweep's
// gen_5076: one leg, NOISE off, no approximation listed): the runs' end
// points sit on the lattice of one cycle's steps and verify's smooth radius
// curve is a few millimetres off, so at Rmax 0.066-0.067 m the 1 % margin
// alone said GO where 4,000 runs clearly say no. About 3 s.
#include <doctest/doctest.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

namespace verifier = p3at::verifier;

namespace {

std::string data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/data/decision_floor/" + name;
}

constexpr double kGo = 0.8;             // the cross-check's threshold for a GO cell
constexpr double kClearlyBelow = 0.78;  // ... and the validation's upper bound that makes it wrong

/// Rmax from 0.055 to 0.085 m by 1 mm: where the radius curve rises.
std::vector<double> fine_rmax() {
  std::vector<double> r;
  for (int mm = 55; mm <= 85; ++mm) r.push_back(mm / 1000.0);
  return r;
}

/// Wrong GO cells: the gate's probability (read at each cell's decision
/// point) at least kGo where the runs' 95 % upper bound is below kClearlyBelow.
std::size_t wrong_go_cells(const std::vector<double>& decided, const std::vector<double>& runs_ci_high) {
  std::size_t n = 0;
  for (std::size_t j = 0; j < decided.size(); ++j) n += decided[j] >= kGo && runs_ci_high[j] < kClearlyBelow;
  return n;
}

}  // namespace

TEST_CASE("the decision point: 1 % stricter, but at least the floors") {
  const verifier::DecisionFloors floors{0.1, 0.03};
  // Short criteria: the floors decide.
  CHECK(verifier::decision_point(5.0, 0.5, false, floors).tmax_s == doctest::Approx(4.9));
  CHECK(verifier::decision_point(5.0, 0.5, false, floors).rmax_m == doctest::Approx(0.47));
  // Long ones: the 1 % does.
  CHECK(verifier::decision_point(200.0, 10.0, false, floors).tmax_s == doctest::Approx(198.0));
  CHECK(verifier::decision_point(200.0, 10.0, false, floors).rmax_m == doctest::Approx(9.9));
  // Never a negative radius; the widening still applies on top.
  CHECK(verifier::decision_point(5.0, 0.02, false, floors).rmax_m == 0.0);
  CHECK(verifier::decision_point(5.0, 0.5, true, floors).tmax_s == doctest::Approx(4.5));
  CHECK(verifier::decision_point(5.0, 0.5, true, floors).rmax_m == doctest::Approx(0.47));
  // No floors: the 1 % alone, as before they existed.
  CHECK(verifier::decision_point(5.0, 0.5, false).rmax_m == doctest::Approx(0.495));
}

TEST_CASE("a mission's floors: its models' cycle and its fastest robot's step") {
  const auto mission = p3at::mission::load_mission_file(data("mission.yaml"));
  const auto models = verifier::load_models_file(data("models.yaml"));
  const verifier::DecisionFloors f = verifier::decision_floors(mission, models);
  CHECK(f.time_s == doctest::Approx(0.1));
  CHECK(f.radius_m == doctest::Approx(0.03));  // 0.3 m/s for 0.1 s
}

TEST_CASE("gen_5076: no GO where 4,000 runs clearly say no, on a 1 mm Rmax grid") {
  const auto mission = p3at::mission::load_mission_file(data("mission.yaml"));
  const auto models = verifier::load_models_file(data("models.yaml"));
  const std::vector<double> rmax = fine_rmax();
  const double tmax = 45.0;  // the mission's own: every run is done by then

  // The runs: the validation's 95 % upper bound at each cell.
  const auto v = p3at::test::run_command(p3at::test::vipars_binary() + " validate " + data("mission.yaml") +
                                         " --world " + data("world.yaml") +
                                         " --trials 4000 --seed 1 --jobs 1 --timeout 120 --tmax-range 45:45:1 "
                                         "--rmax-range 0.055:0.085:0.001 --json");
  REQUIRE(v.status == 0);
  const nlohmann::json runs = nlohmann::json::parse(v.out);
  const std::vector<double> ci_high = runs.at("grid").at("p_joint_ci_high").at(0).get<std::vector<double>>();
  REQUIRE(ci_high.size() == rmax.size());

  // What the gate decides on at each cell, with and without the floors.
  verifier::VerifyOptions plain;
  plain.tmax_s = tmax;
  const auto once = verifier::verify(mission, models, plain);
  REQUIRE(once.ok());
  CHECK(once.value().evaluable);  // nothing listed: the gate would act on it
  const verifier::DecisionFloors floors = once.value().floors;
  const auto decided_at = [&](const verifier::DecisionFloors& f) {
    verifier::VerifyOptions o;
    o.tmax_grid = {verifier::decision_point(tmax, 1.0, false, f).tmax_s};
    for (const double r : rmax) o.rmax_grid.push_back(verifier::decision_point(1.0, r, false, f).rmax_m);
    const auto read = verifier::verify(mission, models, o);
    REQUIRE(read.ok());
    return read.value().grid->p_joint.front();
  };
  const std::size_t before = wrong_go_cells(decided_at({}), ci_high);
  const std::size_t now = wrong_go_cells(decided_at(floors), ci_high);
  MESSAGE("wrong GO cells: 1 % margin alone " << before << ", with the floors " << now);
  CHECK(before >= 1);  // the fault this guards against is real on this mission
  CHECK(now == 0);
}
