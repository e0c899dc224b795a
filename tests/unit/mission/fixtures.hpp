#pragma once
// Mission texts shared by the mission tests, and helpers to derive broken
// variants of them and to locate the node an error must point at.

#include <doctest/doctest.h>

#include <string>
#include <string_view>

#include "p3at/mission/loader.hpp"

namespace p3at::mission::test {

/// A valid two-robot relay; every optional field left to its default.
inline constexpr std::string_view kRelay = R"(mission:
  name: relay
criteria:
  tmax_s: 60
  rmax_m: 0.5
  threshold: 0.8
robots:
  - name: robot1
    start: {x_m: 1.0, y_m: 1.0, theta_deg: 0}
    hal: tcp://127.0.0.1:8101
    states:
      - {name: drive, behavior: GoToGuarded, params: {goal: [3.0, 1.0], dropoff_m: 0.5}}
      - {name: tell, behavior: Notify, params: {message: r1_done}}
      - {name: done, behavior: Stop}
    transitions:
      - {from: drive, to: tell, trigger: AtGoal, params: {radius_m: 0.2}}
      - {from: tell, to: done, trigger: MessageSent}
  - name: robot2
    start: {x_m: 1.0, y_m: 2.0}
    hal: tcp://127.0.0.1:8102
    states:
      - {name: wait, behavior: Stop}
      - {name: drive2, behavior: GoToGuarded, params: {goal: [3.0, 2.0], dropoff_m: 0.5}}
      - {name: finished, behavior: Stop}
    transitions:
      - {from: wait, to: drive2, trigger: Notified, params: {message: r1_done}}
      - {from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}
messages:
  - {name: r1_done, from: robot1, to: [robot2]}
)";

/// A two-robot Bounding Overwatch like the seed paper's (section VI): starts
/// (5.5, 5.0) and (6.5, 5.0), goals (19.75, 18.0) and (20.0, 17.5); the robots
/// leapfrog along a hallway in +X, turn 90 degrees counter-clockwise and go on in +Y.
inline constexpr std::string_view kBoundingOverwatch = R"(mission:
  name: bounding_overwatch
  description: "Two P3-ATs leapfrog down a hallway, turn left, and end near the far goals"
criteria:
  tmax_s: 200
  rmax_m: 2.0
  threshold: 0.8
  abort_threshold: 0.5
  abort_action: stop_and_notify
robots:
  - name: robot1
    start: {x_m: 5.5, y_m: 5.0, theta_deg: 0}
    hal: tcp://127.0.0.1:8101
    initial: wait_a
    states:
      - {name: wait_a, behavior: Stop}
      - {name: go_b, behavior: GoToGuarded, params: {goal: [14.0, 5.0], dropoff_m: 2.5}}
      - {name: tell_b, behavior: Notify, params: {message: r1_at_b}}
      - {name: wait_c, behavior: Stop}
      - {name: go_corner, behavior: GoToGuarded, params: {goal: [19.75, 5.0]}}
      - {name: turn, behavior: Spin, params: {rate_deg_s: 30}}
      - {name: go_goal, behavior: GoToGuarded, params: {goal: [19.75, 18.0]}}
      - {name: tell_goal, behavior: Notify, params: {message: r1_at_goal}}
      - {name: done, behavior: Stop}
    transitions:
      - {from: wait_a, to: go_b, trigger: Notified, params: {message: r2_at_a}}
      - {from: go_b, to: tell_b, trigger: AtGoal, params: {radius_m: 0.3}}
      - {from: tell_b, to: wait_c, trigger: MessageSent}
      - {from: wait_c, to: go_corner, trigger: Notified, params: {message: r2_at_c}}
      - {from: go_corner, to: turn, trigger: AtGoal, params: {radius_m: 0.3}}
      - {from: turn, to: go_goal, trigger: HasTurned, params: {angle_deg: 90}}
      - {from: go_goal, to: tell_goal, trigger: AtGoal, params: {radius_m: 0.3}}
      - {from: tell_goal, to: done, trigger: MessageSent}
  - name: robot2
    start: {x_m: 6.5, y_m: 5.0, theta_deg: 0}
    hal: tcp://127.0.0.1:8102
    states:
      - {name: go_a, behavior: GoToGuarded, params: {goal: [10.0, 5.0]}}
      - {name: tell_a, behavior: Notify, params: {message: r2_at_a}}
      - {name: wait_b, behavior: Stop}
      - {name: go_corner, behavior: GoToGuarded, params: {goal: [20.5, 5.0]}}
      - {name: turn, behavior: Spin, params: {rate_deg_s: 30}}
      - {name: go_c, behavior: GoToGuarded, params: {goal: [21.0, 10.0]}}
      - {name: tell_c, behavior: Notify, params: {message: r2_at_c}}
      - {name: wait_d, behavior: Stop}
      - {name: go_goal, behavior: GoToGuarded, params: {goal: [20.0, 17.5]}}
      - {name: done, behavior: Stop}
    transitions:
      - {from: go_a, to: tell_a, trigger: AtGoal, params: {radius_m: 0.3}}
      - {from: tell_a, to: wait_b, trigger: MessageSent}
      - {from: wait_b, to: go_corner, trigger: Notified, params: {message: r1_at_b}}
      - {from: go_corner, to: turn, trigger: AtGoal, params: {radius_m: 0.3}}
      - {from: turn, to: go_c, trigger: HasTurned, params: {angle_deg: 90, offset_deg: 5}}
      - {from: go_c, to: tell_c, trigger: AtGoal, params: {radius_m: 0.3}}
      - {from: tell_c, to: wait_d, trigger: MessageSent}
      - {from: wait_d, to: go_goal, trigger: Notified, params: {message: r1_at_goal}}
      - {from: go_goal, to: done, trigger: AtGoal, params: {radius_m: 0.3}}
messages:
  - {name: r2_at_a, from: robot2, to: [robot1]}
  - {name: r1_at_b, from: robot1, to: [robot2]}
  - {name: r2_at_c, from: robot2, to: [robot1]}
  - {name: r1_at_goal, from: robot1, to: [robot2]}
)";

/// `text` with the single occurrence of `from` replaced by `to` (fails the test
/// if `from` does not occur exactly once, so a fixture edit cannot go stale).
inline std::string replace_once(std::string_view text, std::string_view from, std::string_view to) {
  std::string out(text);
  const auto at = out.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, "fixture lacks: " << from);
  REQUIRE_MESSAGE(out.find(from, at + 1) == std::string::npos, "fixture has more than one: " << from);
  out.replace(at, from.size(), to);
  return out;
}

/// "line:column" (1-based) of the `nth` (1-based) occurrence of `needle` in
/// `text`. A '|' in the needle marks the spot within it ("threshold: |0").
inline std::string loc(std::string_view text, std::string_view needle, int nth = 1) {
  std::string plain(needle);
  std::size_t shift = 0;
  if (const auto bar = plain.find('|'); bar != std::string::npos) {
    shift = bar;
    plain.erase(bar, 1);
  }
  std::size_t at = std::string_view::npos;
  for (std::size_t from = 0; nth > 0; --nth) {
    at = text.find(plain, from);
    REQUIRE_MESSAGE(at != std::string_view::npos, "text lacks: " << plain);
    from = at + 1;
  }
  at += shift;
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return std::to_string(line) + ":" + std::to_string(at - line_start + 1);
}

/// The full message of the MissionError parsing `text` as "t.yaml" throws, or
/// "no error" if it loads.
inline std::string error_of(std::string_view text) {
  try {
    (void)parse_mission(text, "t.yaml");
  } catch (const MissionError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace p3at::mission::test
