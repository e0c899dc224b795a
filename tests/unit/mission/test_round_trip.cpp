// to_yaml writes a mission that parses back to the same value.

#include <doctest/doctest.h>

#include "fixtures.hpp"
#include "p3at/mission/printer.hpp"

using namespace p3at::mission;
using p3at::mission::test::kBoundingOverwatch;
using p3at::mission::test::kRelay;
using p3at::mission::test::replace_once;

namespace {

void check_round_trip(const Mission& m) {
  const std::string text = to_yaml(m);
  const Mission again = parse_mission(text, "printed.yaml");
  CHECK(again == m);
  CHECK(to_yaml(again) == text);  // canonical: printing is a fixed point
}

}  // namespace

TEST_CASE("the relay and Bounding Overwatch missions round-trip") {
  check_round_trip(parse_mission(kRelay, "relay.yaml"));
  check_round_trip(parse_mission(kBoundingOverwatch, "bo.yaml"));
}

TEST_CASE("the canonical form writes every resolved default") {
  const Mission m = parse_mission(R"(mission: {name: solo}
criteria: {tmax_s: 10, rmax_m: 1.5, threshold: 0.9}
robots:
  - name: r
    start: {x_m: 0.1, y_m: -2}
    hal: tcp://127.0.0.1:8101
    states:
      - {name: go, behavior: GoToGuarded, params: {goal: [1, 0]}}
      - {name: spin, behavior: Spin, params: {rate_deg_s: -45}}
      - {name: stop, behavior: Stop}
    transitions:
      - {from: go, to: spin, trigger: AtGoal, params: {radius_m: 0.25}}
      - {from: spin, to: stop, trigger: HasTurned, params: {angle_deg: 180}}
)", "solo.yaml");
  CHECK(to_yaml(m) ==
        "# Mission file in canonical form (docs/mission-format.md): every default written out.\n"
        "mission:\n"
        "  name: solo\n"
        "criteria:\n"
        "  tmax_s: 10\n"
        "  rmax_m: 1.5\n"
        "  threshold: 0.9\n"
        "  abort_threshold: 0\n"
        "  abort_action: continue_and_warn\n"
        "robots:\n"
        "  - name: r\n"
        "    start: {x_m: 0.1, y_m: -2, theta_deg: 0}\n"
        "    goal: [1, 0]\n"
        "    hal: \"tcp://127.0.0.1:8101\"\n"
        "    lcm: \"udpm://239.255.76.67:7667?ttl=0\"\n"
        "    max_speed_mps: 0.3\n"
        "    initial: go\n"
        "    states:\n"
        "      - {name: go, behavior: GoToGuarded, params: {goal: [1, 0], dropoff_m: 2.5, dead_zone_m: 0.05, "
        "move_gain: 1, avoid_gain: 1, noise_gain: 0.1, sphere_m: 1, safety_margin_m: 0.25, "
        "noise_persistence_cycles: 10}}\n"
        "      - {name: spin, behavior: Spin, params: {rate_deg_s: -45}}\n"
        "      - {name: stop, behavior: Stop}\n"
        "    transitions:\n"
        "      - {from: go, to: spin, trigger: AtGoal, params: {goal: [1, 0], radius_m: 0.25}}\n"
        "      - {from: spin, to: stop, trigger: HasTurned, params: {angle_deg: 180, offset_deg: 0}}\n");
}

TEST_CASE("numbers round-trip bit for bit") {
  Mission m = parse_mission(kRelay, "relay.yaml");
  m.criteria.tmax_s = 1.0 / 3.0;
  m.criteria.rmax_m = 0.1 + 0.2;
  m.criteria.threshold = 1e-300;
  m.robots[0].start = Pose2{-1234.5678901234567, 9999.999999999998, -359.99999999999994};
  m.robots[1].goal = Point2{0.30000000000000004, -7e-5};
  auto& go = std::get<GoToGuardedParams>(m.robots[0].states[0].behavior);
  go.goal = Point2{5e-324, -0.0};
  go.noise_persistence_cycles = 1'000'000;
  go.move_gain = 123.456;
  std::get<AtGoalParams>(m.robots[1].transitions[1].trigger).radius_m = 2.0 / 7.0;
  check_round_trip(m);
}

TEST_CASE("names that look like other YAML types and odd descriptions round-trip") {
  std::string text = replace_once(kRelay, "name: robot2", "name: \"null\"");
  text = replace_once(text, "to: [robot2]", "to: [\"null\"]");
  text = replace_once(text, "{name: wait, behavior: Stop}", "{name: \"Yes\", behavior: Stop}");
  text = replace_once(text, "{from: wait, to: drive2", "{from: \"Yes\", to: drive2");
  text = replace_once(text, "  name: relay\n",
                      "  name: relay\n  description: \"quote \\\" backslash \\\\ tab \\t newline \\n bell \\a "
                      "caf\xc3\xa9 \xe6\x97\xa5\"\n");
  const Mission m = parse_mission(text, "t.yaml");
  CHECK(m.robots[1].name == "null");
  CHECK(m.robots[1].states[0].name == "Yes");
  CHECK(m.description == "quote \" backslash \\ tab \t newline \n bell \a caf\xc3\xa9 \xe6\x97\xa5");
  check_round_trip(m);
}

TEST_CASE("equality sees every field") {
  const Mission base = parse_mission(kBoundingOverwatch, "bo.yaml");
  Mission changed = base;
  CHECK(changed == base);
  std::get<GoToGuardedParams>(changed.robots[1].states[0].behavior).noise_gain = 0.2;
  CHECK_FALSE(changed == base);
  changed = base;
  changed.robots[0].transitions[5].to = 0;
  CHECK_FALSE(changed == base);
  changed = base;
  changed.messages[2].to.push_back(1);
  CHECK_FALSE(changed == base);
  changed = base;
  changed.robots[1].goal.y_m += 1e-12;
  CHECK_FALSE(changed == base);
  changed = base;
  changed.criteria.abort_action = AbortAction::continue_and_warn;
  CHECK_FALSE(changed == base);
}
