// The may-get-trapped check on the legs a run really drives: the mission's
// leg is where the robot believes it goes, and a run drives it moved by the
// pose error it carries (true minus odometry). The evaluation records that
// error at each leg's entry (SystemOutcome::leg_entries); the check tries the
// leg moved by its mean and by two standard deviations either side, and by
// the heading error the leg itself gathers (approximations.cpp, traps()).
//
// The mission: one robot believing it drives 12 m along y = 0; a wall from
// (6.2, 0.9) up to (6.2, 5), its free end 0.9 m to the left of the believed
// path about half-way. The believed leg passes clear; a run whose heading is
// 0.15 rad (8.6 degrees) off to the left is 0.94 m to the left at x = 6.2 and
// meets the wall.

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/verifier/approximations.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

namespace {

using p3at::verifier::ApproximationKind;
using p3at::verifier::LegEntryRecord;
using p3at::verifier::SystemOutcome;

p3at::mission::Mission past_a_wall_end() {
  return p3at::mission::parse_mission("mission: {name: past_a_wall_end}\n"
                                      "criteria: {tmax_s: 200, rmax_m: 1.0, threshold: 0.5}\n"
                                      "robots:\n"
                                      "  - name: r\n"
                                      "    start: {x_m: 0.0, y_m: 0.0, theta_deg: 0}\n"
                                      "    hal: tcp://127.0.0.1:8101\n"
                                      "    states:\n"
                                      "      - {name: go, behavior: GoToGuarded, params: {goal: [12.0, 0.0]}}\n"
                                      "      - {name: done, behavior: Stop}\n"
                                      "    transitions:\n"
                                      "      - {from: go, to: done, trigger: AtGoal, params: {radius_m: 0.3}}\n",
                                      "past_a_wall_end.yaml");
}

/// A robot whose heading error grows by `heading_sd_per_sqrt_m` per sqrt(m)
/// (nothing else random), beside the one wall.
p3at::verifier::Models models(double heading_sd_per_sqrt_m) {
  const std::string text = "models: {version: 1}\n"
                           "robots:\n"
                           "  - name: r\n"
                           "    kinematics: {robot_radius_m: 0.3, calibrated_speed_mps: 0.3, top_speed_mps: 0.6}\n"
                           "    motion: {heading_sd_per_sqrt_m: " +
                           std::to_string(heading_sd_per_sqrt_m) +
                           "}\n"
                           "environment:\n"
                           "  walls: [[6.2, 0.9, 6.2, 5.0]]\n";
  return p3at::verifier::parse_models(text, "models.yaml", ".");
}

/// The leg's entry at the start, with this pose error (x, y, heading).
SystemOutcome entered_with(double heading_mean_rad, double heading_sd_rad, std::size_t state = 0) {
  SystemOutcome o;
  LegEntryRecord e;
  e.robot = 0;
  e.state = state;
  e.error_mean(2) = heading_mean_rad;
  e.error_cov(2, 2) = heading_sd_rad * heading_sd_rad;
  o.leg_entries.push_back(e);
  return o;
}

std::vector<std::string> trapped(const SystemOutcome& outcome, double heading_sd_per_sqrt_m = 0.0) {
  std::vector<std::string> details;
  for (const auto& a : p3at::verifier::detect_approximations(past_a_wall_end(), models(heading_sd_per_sqrt_m), outcome)) {
    if (a.kind == ApproximationKind::may_get_trapped) details.push_back(a.state + ": " + a.detail);
  }
  return details;
}

}  // namespace

TEST_CASE("the believed leg passes clear of the wall's end: not flagged, before or without an error") {
  CHECK(trapped(SystemOutcome{}).empty());
  CHECK(trapped(entered_with(0.0, 0.0)).empty());
  for (const auto& a : p3at::verifier::detect_approximations_before_evaluation(past_a_wall_end(), models(0.0))) {
    CHECK(a.kind != ApproximationKind::may_get_trapped);
  }
}

TEST_CASE("a mean heading error that turns the run into the wall: flagged, saying it is the run's error") {
  const auto found = trapped(entered_with(0.15, 0.0));
  REQUIRE(found.size() == 1);
  CHECK(found[0].find("go: with the pose error a run may carry") == 0);
  CHECK(found[0].find("a wall (6.20, 0.90)-(6.20, 5.00) lies across the leg") != std::string::npos);
  // Turned the other way, the run leaves the wall further off.
  CHECK(trapped(entered_with(-0.15, 0.0)).empty());
}

TEST_CASE("the error's tails: two standard deviations either side reach the wall, one does not") {
  CHECK(trapped(entered_with(0.0, 0.08)).size() == 1);  // 2 sd = 0.16 rad: 0.99 m off at x = 6.2
  CHECK(trapped(entered_with(0.0, 0.06)).empty());      // 2 sd = 0.12 rad: 0.74 m off
  // The tails count on the side of the wall only: a mean turned away, the
  // same spread, stays clear.
  CHECK(trapped(entered_with(-0.05, 0.08)).empty());
}

TEST_CASE("the heading error the leg itself gathers counts too") {
  // No error at the entry; heading variance per metre h: 2 sd of the
  // sideways offset s metres along are 2 sqrt(h s^3 / 3), at x = 6.2 17.8 sqrt(h).
  CHECK(trapped(entered_with(0.0, 0.0), 0.07).size() == 1);  // h = 0.0049: 1.25 m
  CHECK(trapped(entered_with(0.0, 0.0), 0.03).empty());      // h = 0.0009: 0.53 m
}

TEST_CASE("an entry recorded for another state says nothing about this one") {
  CHECK(trapped(entered_with(0.15, 0.0, 1)).empty());
}

TEST_CASE("the evaluation records each leg's entry, and verify flags the run's gathered error") {
  const auto outcome = p3at::verifier::evaluate_system(past_a_wall_end(), models(0.07));
  REQUIRE(outcome.ok());
  REQUIRE(outcome->leg_entries.size() == 1);
  CHECK(outcome->leg_entries[0].state == 0);
  CHECK(outcome->leg_entries[0].x0_m == doctest::Approx(0.0));
  p3at::verifier::VerifyOptions options;
  const auto verdict = p3at::verifier::verify(past_a_wall_end(), models(0.07), options);
  REQUIRE(verdict.ok());
  bool flagged = false;
  for (const auto& a : verdict->approximations) flagged |= a.kind == ApproximationKind::may_get_trapped;
  CHECK(flagged);
  const auto steady = p3at::verifier::verify(past_a_wall_end(), models(0.0), options);
  REQUIRE(steady.ok());
  for (const auto& a : steady->approximations) CHECK(a.kind != ApproximationKind::may_get_trapped);
}
