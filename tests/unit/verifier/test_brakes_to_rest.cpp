// Which states a leg's paths run out their own braking into
// (engine/state_analysis.hpp, brakes_to_rest): a Stop or a final state; a
// Spin only if its turn outlasts braking from the robot's top speed; a Notify
// only if its acknowledgement leads to such states alone, never through a
// cycle of Notifies.
#include <doctest/doctest.h>

#include <cstddef>
#include <string>

#include "engine/state_analysis.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"

namespace {

using p3at::mission::Mission;

/// A two-robot mission whose robot1 drives a leg at 0.6 m/s and then goes
/// through `states` / `transitions` (YAML flow lines, already indented),
/// sending `messages` (YAML flow lines) to robot2, which only receives.
Mission scout(const std::string& states, const std::string& transitions, const std::string& messages = "") {
  const std::string text =
      "mission: {name: brakes}\n"
      "criteria: {tmax_s: 100, rmax_m: 1.0, threshold: 0.8}\n"
      "robots:\n"
      "  - name: robot1\n"
      "    start: {x_m: 1, y_m: 1, theta_deg: 0}\n"
      "    hal: tcp://127.0.0.1:8101\n"
      "    max_speed_mps: 0.6\n"
      "    states:\n"
      "      - {name: leg, behavior: GoToGuarded, params: {goal: [8, 1]}}\n" +
      states +
      "    transitions:\n"
      "      - {from: leg, to: next, trigger: AtGoal, params: {radius_m: 0.3}}\n" +
      transitions +
      "  - name: robot2\n"
      "    start: {x_m: 1, y_m: 5, theta_deg: 0}\n"
      "    hal: tcp://127.0.0.1:8102\n"
      "    states:\n"
      "      - {name: wait, behavior: Stop}\n" +
      (messages.empty() ? std::string() : "messages:\n" + messages);
  return p3at::mission::parse_mission(text, "brakes.yaml");
}

const std::string kSendsA = "  - {name: a, from: robot1, to: [robot2]}\n";
const std::string kSendsAB = kSendsA + "  - {name: b, from: robot1, to: [robot2]}\n";

/// Whether robot1's state `next` (what its leg's AtGoal leads to) brakes to rest.
bool next_brakes(const Mission& m, const p3at::verifier::Kinematics& kin) {
  const auto& robot = m.robots.at(0);
  for (std::size_t s = 0; s < robot.states.size(); ++s) {
    if (robot.states[s].name == "next") return p3at::verifier::engine::brakes_to_rest(robot, s, kin);
  }
  FAIL("no state 'next'");
  return false;
}

}  // namespace

TEST_CASE("a Notify brakes to rest when its acknowledgement leads only to still states") {
  const p3at::verifier::Kinematics kin;
  // Notify -> Stop (final): the Stop finishes the braking the acknowledgement cut.
  CHECK(next_brakes(scout("      - {name: next, behavior: Notify, params: {message: a}}\n"
                          "      - {name: done, behavior: Stop}\n",
                          "      - {from: next, to: done, trigger: MessageSent}\n", kSendsA),
                    kin));
  // Notify -> Notify -> Stop: still the whole way.
  CHECK(next_brakes(scout("      - {name: next, behavior: Notify, params: {message: a}}\n"
                          "      - {name: again, behavior: Notify, params: {message: b}}\n"
                          "      - {name: done, behavior: Stop}\n",
                          "      - {from: next, to: again, trigger: MessageSent}\n"
                          "      - {from: again, to: done, trigger: MessageSent}\n", kSendsAB),
                    kin));
  // Notify -> another leg: the robot may drive on before it is at rest.
  CHECK_FALSE(next_brakes(scout("      - {name: next, behavior: Notify, params: {message: a}}\n"
                                "      - {name: on, behavior: GoToGuarded, params: {goal: [8, 6]}}\n"
                                "      - {name: done, behavior: Stop}\n",
                                "      - {from: next, to: on, trigger: MessageSent}\n"
                                "      - {from: on, to: done, trigger: AtGoal, params: {radius_m: 0.3}}\n", kSendsA),
                          kin));
  // Two Notifies that lead to each other (until a Spin long enough to brake
  // in takes the robot out): the cycle is not counted.
  CHECK_FALSE(next_brakes(scout("      - {name: next, behavior: Notify, params: {message: a}}\n"
                                "      - {name: again, behavior: Notify, params: {message: b}}\n"
                                "      - {name: turn, behavior: Spin, params: {rate_deg_s: 40}}\n"
                                "      - {name: done, behavior: Stop}\n",
                                "      - {from: next, to: again, trigger: MessageSent}\n"
                                "      - {from: again, to: next, trigger: MessageSent}\n"
                                "      - {from: again, to: turn, trigger: MessageSent}\n"
                                "      - {from: turn, to: done, trigger: HasTurned, params: {angle_deg: 360}}\n",
                                kSendsAB),
                          kin));
}

TEST_CASE("a Spin brakes to rest only if its turn outlasts braking from the top speed") {
  p3at::verifier::Kinematics kin;
  kin.trans_decel_mps2 = 0.6;  // 0.6 m/s brakes in 1.0 s, plus a cycle: 1.1 s
  const auto spin_then_stop = [](const std::string& angle) {
    return scout("      - {name: next, behavior: Spin, params: {rate_deg_s: 40}}\n"
                 "      - {name: done, behavior: Stop}\n",
                 "      - {from: next, to: done, trigger: HasTurned, params: {angle_deg: " + angle + "}}\n");
  };
  CHECK(next_brakes(spin_then_stop("90"), kin));         // 2.25 s at 40 deg/s
  CHECK(next_brakes(spin_then_stop("45"), kin));         // 1.125 s
  CHECK_FALSE(next_brakes(spin_then_stop("40"), kin));   // 1.0 s: may end while the robot still moves
  kin.max_rot_vel_radps = 20.0 * 3.14159265358979323846 / 180.0;  // the firmware allows only 20 deg/s
  CHECK(next_brakes(spin_then_stop("40"), kin));         // 2.0 s
  // A Notify whose acknowledgement leads into a long enough Spin brakes to rest too.
  CHECK(next_brakes(scout("      - {name: next, behavior: Notify, params: {message: a}}\n"
                          "      - {name: turn, behavior: Spin, params: {rate_deg_s: 40}}\n"
                          "      - {name: done, behavior: Stop}\n",
                          "      - {from: next, to: turn, trigger: MessageSent}\n"
                          "      - {from: turn, to: done, trigger: HasTurned, params: {angle_deg: 90}}\n", kSendsA),
                    kin));
}
