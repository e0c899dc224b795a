// The verifier's work budget (Budget::max_work_cycles): a mission whose
// within-state models would simulate more robot cycles than the budget is
// cut off deterministically, and the mass left unevaluated is reported and
// counted as failure, so the answer is a lower bound on success (never a GO
// the model did not compute).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "outcome_mass.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

using namespace p3at;
using namespace p3at::verifier;

namespace {

const std::string kExample = std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/";

}  // namespace

TEST_CASE("work budget: the default leaves a shipped mission whole; a small one cuts it off as failure") {
  const mission::Mission m = mission::load_mission_file(kExample + "mission.yaml");
  const Models models = load_models_file(kExample + "models.yaml");
  Result<SystemOutcome> whole = evaluate_system(m, models);
  REQUIRE(whole);
  CHECK(whole->work_cutoff_mass == 0.0);
  CHECK(whole->work_cycles > 0);
  CHECK(whole->work_cycles < models.budget.max_work_cycles);
  Result<VerifyResult> full = verify(m, models, VerifyOptions{});
  REQUIRE(full);
  REQUIRE(full->p_joint > 0.2);  // the cut-off answer below must be lower
  CHECK(full->work_cycles == whole->work_cycles);

  Models tight = models;
  tight.budget.max_work_cycles = whole->work_cycles / 4;
  Result<SystemOutcome> cut = evaluate_system(m, tight);
  REQUIRE(cut);
  CHECK(cut->work_cutoff_mass > 0.5);
  CHECK(test::accounted_mass(*cut) == doctest::Approx(1.0).epsilon(1e-9));
  // Stopped at the first event after the budget ran out: about the budget's work, not the whole mission's.
  CHECK(cut->work_cycles < whole->work_cycles);
  Result<VerifyResult> r = verify(m, tight, VerifyOptions{});
  REQUIRE(r);
  CHECK(r->work_cutoff_mass == doctest::Approx(cut->work_cutoff_mass));
  CHECK(r->p_joint <= 1.0 - cut->work_cutoff_mass + 1e-12);
  CHECK(r->p_joint < full->p_joint);

  // Deterministic: the same cut every time (a count of cycles, not a clock).
  Result<SystemOutcome> again = evaluate_system(m, tight);
  REQUIRE(again);
  CHECK(again->work_cycles == cut->work_cycles);
  CHECK(again->work_cutoff_mass == cut->work_cutoff_mass);
}

TEST_CASE("work budget: past half of it, a leg entered from a new place takes the nearest place's analysis, flagged") {
  // A patrol until relieved: each lap enters the same two legs again with a
  // grown pose error, so each lap is new analyses, and the laps are what a
  // budget cuts off (gen_7610, gen_7577: P 0 where the runs finish).
  const mission::Mission m =
      mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/patrol.yaml");
  Models models = load_models_file(kExample + "models.yaml");
  models.environment.walls.clear();  // the beat is open floor
  Result<SystemOutcome> whole = evaluate_system(m, models);
  REQUIRE(whole);
  REQUIRE(whole->work_cutoff_mass == 0.0);
  REQUIRE(whole->budget_merged_mass == 0.0);
  REQUIRE_FALSE(whole->work_pressure_merged);
  Result<VerifyResult> full = verify(m, models, VerifyOptions{});
  REQUIRE(full);
  REQUIRE(full->p_joint > 0.5);

  // Nine tenths of the work the whole evaluation simulates: without the
  // reuse the last lap's legs would be cut off as failure. (At three
  // quarters they still are: the budget runs out inside a leg's first entry,
  // which has no earlier place to take an analysis from.)
  Models tight = models;
  tight.budget.max_work_cycles = whole->work_cycles * 9 / 10;
  Result<SystemOutcome> reused = evaluate_system(m, tight);
  REQUIRE(reused);
  CHECK(reused->work_pressure_merged);
  CHECK(reused->work_cutoff_mass == 0.0);
  CHECK(reused->budget_merged_mass > 0.0);
  CHECK(reused->work_cycles < whole->work_cycles);
  // Each record says which budget merged it: here only the work budget did.
  REQUIRE_FALSE(reused->budget_merges.empty());
  for (const BudgetMerge& b : reused->budget_merges) {
    CHECK(b.work_budget);
    CHECK_FALSE(b.branch_budget);
  }
  CHECK(test::accounted_mass(*reused) == doctest::Approx(1.0).epsilon(1e-9));
  Result<VerifyResult> r = verify(m, tight, VerifyOptions{});
  REQUIRE(r);
  // The coarser picture is close to the whole one, and the gate does not vouch for it.
  CHECK(std::abs(r->p_joint - full->p_joint) <= 0.05);
  const bool flagged = std::any_of(r->approximations.begin(), r->approximations.end(), [](const Approximation& a) {
    return a.kind == ApproximationKind::places_merged_over_budget && !a.vouched &&
           a.detail.find("max_work_cycles") != std::string::npos &&
           a.detail.find("max_branches") == std::string::npos;
  });
  CHECK(flagged);
  CHECK_FALSE(r->evaluable);
}
