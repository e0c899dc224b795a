// A teammate waiting for a message that is already on its way is not a wall
// (engine/sequencer.cpp, released_in): it drives off when the message lands.
// tests/data/accuracy/released_teammate: robot1 sends robot2 off and drives
// east through the edge of the place where robot2 waited; robot2 is at its
// goal, 3.6 m north, by the time robot1 gets there. robot1's leg must come out as if
// robot2 had never stood in its way. The same mission against 1,000
// validation runs is in the accuracy gate (tests/unit/crosscheck).
#include <doctest/doctest.h>

#include <string>

#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

using namespace p3at;
using namespace p3at::verifier;

namespace {

const std::string kDir = std::string(P3AT_SOURCE_DIR) + "/tests/data/accuracy/released_teammate/";

const RobotPrediction& robot1_of(const VerifyResult& r) {
  REQUIRE(r.robots.size() == 2);
  REQUIRE(r.robots[0].name == "robot1");
  return r.robots[0];
}

/// The mission with robot1's leg before its Notify (leg1, then tell_r1_go,
/// then done) and robot2 waiting at (6, y): r1_go is sent only once robot1
/// is at its goal.
mission::Mission leg_before_notify(const mission::Mission& m, double robot2_y_m) {
  mission::Mission out = m;
  mission::RobotSpec& r1 = out.robots[0];
  REQUIRE(r1.states.size() == 3);
  REQUIRE(r1.states[0].name == "tell_r1_go");
  REQUIRE(r1.states[1].name == "leg1");
  r1.initial = 1;
  for (mission::Transition& t : r1.transitions) {
    if (t.from == 0) t.to = 2;  // tell_r1_go -> done (on MessageSent)
    if (t.from == 1) t.to = 0;  // leg1 -> tell_r1_go (AtGoal)
  }
  out.robots[1].start.y_m = robot2_y_m;
  return out;
}

}  // namespace

TEST_CASE("robot1 drives through where a released teammate waited as if it had never been there") {
  const mission::Mission m = mission::load_mission_file(kDir + "mission.yaml");
  const Models models = load_models_file(kDir + "models.yaml");
  const auto with = verify(m, models, VerifyOptions{});
  REQUIRE(with.ok());

  // The same mission with robot2 waiting off robot1's way, 3 m north of the
  // line (its leg north is then shorter; robot1 never comes near it).
  mission::Mission away = m;
  REQUIRE(away.robots.size() == 2);
  away.robots[1].start.y_m = 8.0;
  const auto without = verify(away, models, VerifyOptions{});
  REQUIRE(without.ok());

  const RobotPrediction& a = robot1_of(*with);
  const RobotPrediction& b = robot1_of(*without);
  REQUIRE(a.finishes);
  REQUIRE(b.finishes);
  // Pictured as a wall where it waited, robot2 cost robot1 0.15 s on average
  // and widened its finish from 0.20 s to 1.06 s (sd): its paths steered
  // around the empty place, some a long way.
  CHECK(a.finish_mean_s == doctest::Approx(b.finish_mean_s).epsilon(0.002));
  CHECK(a.finish_sd_s < b.finish_sd_s + 0.05);
  CHECK(a.dist_mean_m == doctest::Approx(b.dist_mean_m).epsilon(0.01));
}

TEST_CASE("a teammate waiting for a message nobody has sent yet is still an obstacle for good") {
  // robot1 drives first and sends r1_go only at its goal: robot2 waits in
  // the way for the whole leg, and robot1 must go around it.
  const mission::Mission m = mission::load_mission_file(kDir + "mission.yaml");
  const Models models = load_models_file(kDir + "models.yaml");
  const auto held = verify(leg_before_notify(m, 5.4), models, VerifyOptions{});
  const auto clear = verify(leg_before_notify(m, 8.0), models, VerifyOptions{});
  REQUIRE(held.ok());
  REQUIRE(clear.ok());
  const RobotPrediction& a = robot1_of(*held);
  const RobotPrediction& b = robot1_of(*clear);
  REQUIRE(a.finishes);
  REQUIRE(b.finishes);
  CHECK(a.finish_mean_s > b.finish_mean_s + 0.05);
  CHECK(a.finish_sd_s > b.finish_sd_s + 0.3);
}
