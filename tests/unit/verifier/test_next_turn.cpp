// What a state's end points are ordered by (engine/next_turn.hpp): the next
// leg's goal when every self-timed exit reaches one (through Stops and
// Notifies), the heading when a Spin comes next, else nothing (where around
// the goal). A message's exit out of the state is not followed: a robot taken
// out by a message is placed by the interruption model, not by these points.
#include <doctest/doctest.h>

#include <cstddef>
#include <string>

#include "engine/next_turn.hpp"
#include "p3at/mission/loader.hpp"

namespace {

using p3at::verifier::engine::next_turn;
using p3at::verifier::engine::NextTurn;

/// robot1 drives `leg` and then goes through `states` / `transitions` (YAML
/// flow lines, already indented), sending `r` if `sends_r`; robot2 sends `m`.
p3at::mission::Mission robot(const std::string& states, const std::string& transitions, bool sends_r = false) {
  const std::string text =
      "mission: {name: next}\n"
      "criteria: {tmax_s: 100, rmax_m: 1.0, threshold: 0.8}\n"
      "robots:\n"
      "  - name: robot1\n"
      "    start: {x_m: 1, y_m: 1, theta_deg: 0}\n"
      "    hal: tcp://127.0.0.1:8101\n"
      "    goal: [8, 1]\n"
      "    states:\n"
      "      - {name: leg, behavior: GoToGuarded, params: {goal: [8, 1]}}\n" +
      states +
      "    transitions:\n" + transitions +
      "  - name: robot2\n"
      "    start: {x_m: 1, y_m: 5, theta_deg: 0}\n"
      "    hal: tcp://127.0.0.1:8102\n"
      "    states:\n"
      "      - {name: wait, behavior: Notify, params: {message: m}}\n"
      "      - {name: done, behavior: Stop}\n"
      "    transitions:\n"
      "      - {from: wait, to: done, trigger: MessageSent}\n"
      "messages:\n"
      "  - {name: m, from: robot2, to: [robot1]}\n" +
      std::string(sends_r ? "  - {name: r, from: robot1, to: [robot2]}\n" : "");
  return p3at::mission::parse_mission(text, "next.yaml");
}

/// What next_turn says after robot1's leg, copied out while the mission (which
/// NextTurn::leg points into) is alive.
struct AfterLeg {
  NextTurn::Kind kind = NextTurn::Kind::unknown;
  bool has_leg = false;
  p3at::mission::Point2 goal;
};

AfterLeg after_leg(const p3at::mission::Mission& m) {
  const NextTurn n = next_turn(m.robots.at(0), 0);
  return {n.kind, n.leg != nullptr, n.leg != nullptr ? n.leg->goal : p3at::mission::Point2{}};
}

}  // namespace

TEST_CASE("the next leg's goal, straight after the leg or through a Notify and a waiting Stop") {
  const AfterLeg direct = after_leg(robot("      - {name: leg2, behavior: GoToGuarded, params: {goal: [3, 6]}}\n",
                                          "      - {from: leg, to: leg2, trigger: AtGoal, params: {radius_m: 0.3}}\n"));
  CHECK(direct.kind == NextTurn::Kind::leg);
  REQUIRE(direct.has_leg);
  CHECK(direct.goal.x_m == 3.0);
  CHECK(direct.goal.y_m == 6.0);
  const AfterLeg through = after_leg(
      robot("      - {name: tell, behavior: Notify, params: {message: r}}\n"
            "      - {name: hold, behavior: Stop}\n"
            "      - {name: leg2, behavior: GoToGuarded, params: {goal: [-2, 4]}}\n",
            "      - {from: leg, to: tell, trigger: AtGoal, params: {radius_m: 0.3}}\n"
            "      - {from: tell, to: hold, trigger: MessageSent}\n"
            "      - {from: hold, to: leg2, trigger: Notified, params: {message: m}}\n",
            true));
  CHECK(through.kind == NextTurn::Kind::leg);
  REQUIRE(through.has_leg);
  CHECK(through.goal.x_m == -2.0);
  CHECK(through.goal.y_m == 4.0);
}

TEST_CASE("a Spin next carries the heading") {
  const AfterLeg spin = after_leg(robot("      - {name: turn, behavior: Spin, params: {rate_deg_s: 30}}\n"
                                        "      - {name: leg2, behavior: GoToGuarded, params: {goal: [3, 6]}}\n",
                                        "      - {from: leg, to: turn, trigger: AtGoal, params: {radius_m: 0.3}}\n"
                                        "      - {from: turn, to: leg2, trigger: HasTurned, params: {angle_deg: 90}}\n"));
  CHECK(spin.kind == NextTurn::Kind::spin);
}

TEST_CASE("nothing to order by: a final state, or two exits toward different goals") {
  CHECK(after_leg(robot("      - {name: done, behavior: Stop}\n",
                        "      - {from: leg, to: done, trigger: AtGoal, params: {radius_m: 0.3}}\n"))
            .kind == NextTurn::Kind::unknown);
  CHECK(after_leg(robot("      - {name: a, behavior: GoToGuarded, params: {goal: [3, 6]}}\n"
                        "      - {name: b, behavior: GoToGuarded, params: {goal: [9, 9]}}\n",
                        "      - {from: leg, to: a, trigger: AtGoal, params: {radius_m: 0.3}}\n"
                        "      - {from: leg, to: b, trigger: AtGoal, params: {radius_m: 0.6}}\n"))
            .kind == NextTurn::Kind::unknown);
  // Two exits to legs with one goal still agree on it.
  const AfterLeg same = after_leg(robot("      - {name: a, behavior: GoToGuarded, params: {goal: [3, 6]}}\n"
                                        "      - {name: b, behavior: GoToGuarded, params: {goal: [3, 6]}}\n",
                                        "      - {from: leg, to: a, trigger: AtGoal, params: {radius_m: 0.3}}\n"
                                        "      - {from: leg, to: b, trigger: AtGoal, params: {radius_m: 0.6}}\n"));
  CHECK(same.kind == NextTurn::Kind::leg);
  REQUIRE(same.has_leg);
  CHECK(same.goal.x_m == 3.0);
}

TEST_CASE("a message's exit out of the leg is not followed") {
  const AfterLeg n = after_leg(robot("      - {name: home, behavior: GoToGuarded, params: {goal: [0, 0]}}\n"
                                     "      - {name: leg2, behavior: GoToGuarded, params: {goal: [3, 6]}}\n",
                                     "      - {from: leg, to: home, trigger: Notified, params: {message: m}}\n"
                                     "      - {from: leg, to: leg2, trigger: AtGoal, params: {radius_m: 0.3}}\n"));
  CHECK(n.kind == NextTurn::Kind::leg);
  REQUIRE(n.has_leg);
  CHECK(n.goal.x_m == 3.0);
  CHECK(n.goal.y_m == 6.0);
}

TEST_CASE("a loop of still states ends the search") {
  // a -> b -> a, and b's way out only to a final Stop.
  const AfterLeg n = after_leg(robot("      - {name: a, behavior: Notify, params: {message: r}}\n"
                                     "      - {name: b, behavior: Stop}\n"
                                     "      - {name: done, behavior: Stop}\n",
                                     "      - {from: leg, to: a, trigger: AtGoal, params: {radius_m: 0.3}}\n"
                                     "      - {from: a, to: b, trigger: MessageSent}\n"
                                     "      - {from: b, to: a, trigger: Notified, params: {message: m}}\n"
                                     "      - {from: b, to: done, trigger: Notified, params: {message: m}}\n",
                                     true));
  CHECK(n.kind == NextTurn::Kind::unknown);
}
