// Over the branch budget (engine/sequencer.cpp, merge_and_prune): a branch
// beyond Budget::max_branches that differs from a kept one only in where a
// message found a robot joins it instead of being dropped as failure, and the
// answer says so (places-merged-over-budget, unvouched). recall_mid_leg's
// recall splits the mission into twelve branches, one per bin of where the
// recall found robot1.
#include <doctest/doctest.h>

#include <string>

#include "outcome_mass.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

using namespace p3at;
using namespace p3at::verifier;

namespace {

const std::string kDir = std::string(P3AT_SOURCE_DIR) + "/tests/data/accuracy/recall_mid_leg/";

Models with_budget(std::size_t max_branches) {
  Models models = load_models_file(kDir + "models.yaml");
  models.budget.max_branches = max_branches;
  return models;
}

bool lists_budget_merge(const VerifyResult& r) {
  for (const Approximation& a : r.approximations) {
    if (a.kind == ApproximationKind::places_merged_over_budget) {
      CHECK(!a.vouched);
      CHECK(a.robot_name == "robot1");
      return true;
    }
  }
  return false;
}

}  // namespace

TEST_CASE("within the budget nothing is merged, and the twelve bins are carried") {
  const mission::Mission m = mission::load_mission_file(kDir + "mission.yaml");
  const auto o = evaluate_system(m, with_budget(32));
  REQUIRE(o.ok());
  CHECK(o->branches.size() == 12);
  CHECK(o->pruned_mass < 1e-9);
  CHECK(o->budget_merged_mass == 0.0);
  CHECK(o->budget_merges.empty());
  const auto r = verify(m, with_budget(32), VerifyOptions{});
  REQUIRE(r.ok());
  CHECK(!lists_budget_merge(*r));
}

TEST_CASE("over the budget the bins merge: no mass is lost, and the answer is not vouched for") {
  const mission::Mission m = mission::load_mission_file(kDir + "mission.yaml");
  const auto full = verify(m, with_budget(32), VerifyOptions{});
  REQUIRE(full.ok());
  for (const std::size_t budget : {4u, 8u}) {
    CAPTURE(budget);
    const auto o = evaluate_system(m, with_budget(budget));
    REQUIRE(o.ok());
    CHECK(o->branches.size() <= budget);
    // Dropping the eight or four lightest bins lost 0.67 / 0.35 of the mass
    // (counted as failure: P(t <= Tmax) 0.33 / 0.65 where it is 1).
    CHECK(o->pruned_mass < 1e-9);
    CHECK(test::accounted_mass(*o) == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(o->budget_merged_mass > 0.5);  // the merged branches' share: 1.00 at 4, 0.75 at 8
    REQUIRE(o->budget_merges.size() == 1);
    CHECK(o->budget_merges[0].robot == 0);
    CHECK(o->budget_merges[0].branch_budget);
    CHECK_FALSE(o->budget_merges[0].work_budget);

    const auto r = verify(m, with_budget(budget), VerifyOptions{});
    REQUIRE(r.ok());
    CHECK(r->p_time == doctest::Approx(full->p_time).epsilon(1e-6));
    CHECK(r->completion_mean_s == doctest::Approx(full->completion_mean_s).epsilon(1e-6));
    // The merged places are one coarser picture of where robot1 stops: close
    // to the twelve's answer here, but not the model's own, so the gate
    // refuses it unless the operator accepts.
    CHECK(r->p_radius == doctest::Approx(full->p_radius).epsilon(0.05));
    CHECK(r->budget_merged_mass == doctest::Approx(o->budget_merged_mass));
    CHECK(lists_budget_merge(*r));
    CHECK(!r->evaluable);
  }
}

TEST_CASE("a branch whose configuration no kept branch shares is still dropped, and counted") {
  const mission::Mission m = mission::load_mission_file(kDir + "mission.yaml");
  // One branch: the bins still merge into it, but a branch in another
  // configuration (an ordering of the two robots' events) has nothing to
  // join and is dropped as failure, as before.
  const auto o = evaluate_system(m, with_budget(1));
  REQUIRE(o.ok());
  CHECK(o->branches.size() == 1);
  CHECK(o->pruned_mass > 0.01);
  CHECK(o->budget_merged_mass > 0.9);
  CHECK(test::accounted_mass(*o) == doctest::Approx(1.0).epsilon(1e-9));
}
