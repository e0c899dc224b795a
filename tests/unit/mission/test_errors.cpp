// One test per error the loader gives (docs/mission-format.md, "Errors"):
// each asserts the exact file:line:column of the offending node and the text.

#include <doctest/doctest.h>

#include "fixtures.hpp"

using p3at::mission::test::error_of;
using p3at::mission::test::kRelay;
using p3at::mission::test::loc;
using p3at::mission::test::replace_once;

namespace {

// The error parsing kRelay with `from` replaced by `to`, expected at the first
// occurrence of `at` in the edited text (or nth), with message `detail`.
void check_edit(std::string_view from, std::string_view to, std::string_view at, const std::string& detail,
                int nth = 1) {
  const std::string text = replace_once(kRelay, from, to);
  CHECK(error_of(text) == "t.yaml:" + loc(text, at, nth) + ": " + detail);
}

}  // namespace

TEST_CASE("the fixture itself is valid") { CHECK(error_of(kRelay) == "no error"); }

TEST_CASE("the location format is file:line:column, 1-based, at the offending node") {
  const std::string text = replace_once(kRelay, "behavior: Notify", "behavior: Notfy");
  // Line 13 is "      - {name: tell, behavior: Notfy, ...": the value starts in column 32.
  CHECK(error_of(text) == "t.yaml:13:32: unknown behavior 'Notfy' (expected one of GoToGuarded, Spin, Stop, Notify)");
}

TEST_SUITE("malformed YAML") {
  TEST_CASE("a syntax error is yaml-cpp's own message at its line:column") {
    // yaml-cpp notices the unclosed flow mapping only at the next block entry.
    const std::string text = replace_once(kRelay, "{name: done, behavior: Stop}", "{name: done, behavior: Stop");
    CHECK(error_of(text) == "t.yaml:16:7: malformed YAML: illegal block entry");
  }
  TEST_CASE("a second colon in a plain value") {
    const std::string text = replace_once(kRelay, "  rmax_m: 0.5", "  rmax_m: 0.5: 1");
    CHECK(error_of(text) == "t.yaml:5:14: malformed YAML: illegal map value");
  }
  TEST_CASE("bad indentation") {
    const std::string text = replace_once(kRelay, "  rmax_m: 0.5", " rmax_m: 0.5");
    CHECK(error_of(text) == "t.yaml:" + loc(text, "rmax_m") + ": malformed YAML: end of map not found");
  }
  TEST_CASE("a stray ',' at the top level (yaml-cpp 0.7 would loop forever on it)") {
    CHECK(error_of(",") == "t.yaml:1:1: malformed YAML: unexpected ','");
    CHECK(error_of(", robots") == "t.yaml:1:1: malformed YAML: unexpected ','");
    const std::string text = std::string(kRelay) + "---\n,\n";
    CHECK(error_of(text) == "t.yaml:" + loc(text, "---\n|,") + ": malformed YAML: unexpected ','");
  }
  TEST_CASE("an empty file") {
    CHECK(error_of("") == "t.yaml:1:1: empty mission (expected a mapping with keys mission, criteria, robots, messages)");
    CHECK(error_of("# only a comment\n") ==
          "t.yaml:1:1: empty mission (expected a mapping with keys mission, criteria, robots, messages)");
    CHECK(error_of("---\n---\n~\n") ==
          "t.yaml:1:1: empty mission (expected a mapping with keys mission, criteria, robots, messages)");
  }
  TEST_CASE("a second document") {
    const std::string text = std::string(kRelay) + "---\nmission: {name: other}\n";
    CHECK(error_of(text) == "t.yaml:" + loc(text, "mission: {name: other}") +
                                ": expected a single YAML document, found a second one");
    // Empty documents before or after the mission are not a second mission.
    CHECK(error_of(std::string(kRelay) + "---\n") == "no error");
    CHECK(error_of("---\n---\n" + std::string(kRelay) + "...\n---\n") == "no error");
  }
  TEST_CASE("a top level that is not a mapping") {
    CHECK(error_of("- mission\n- robots\n") == "t.yaml:1:1: expected a mapping at the top level, got a list");
  }
}

TEST_SUITE("unknown keys: typos are never ignored") {
  TEST_CASE("at the top level") {
    check_edit("messages:\n", "mesages:\n", "mesages",
               "unknown key 'mesages' at the top level (expected one of mission, criteria, robots, messages)");
  }
  TEST_CASE("in mission") {
    check_edit("  name: relay\n", "  name: relay\n  desc: x\n", "desc",
               "unknown key 'desc' in mission (expected one of name, description)");
  }
  TEST_CASE("in criteria") {
    check_edit("tmax_s: 60", "tmax: 60", "tmax",
               "unknown key 'tmax' in criteria (expected one of tmax_s, rmax_m, threshold, abort_threshold, "
               "abort_action)");
  }
  TEST_CASE("in robot") {
    check_edit("hal: tcp://127.0.0.1:8102", "hall: tcp://127.0.0.1:8102", "hall",
               "unknown key 'hall' in robot (expected one of name, start, goal, hal, lcm, max_speed_mps, initial, "
               "states, transitions)");
  }
  TEST_CASE("in start") {
    check_edit("{x_m: 1.0, y_m: 2.0}", "{x_m: 1.0, y: 2.0}", "y: 2.0",
               "unknown key 'y' in start (expected one of x_m, y_m, theta_deg)");
  }
  TEST_CASE("in state") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behaviour: Stop}", "behaviour",
               "unknown key 'behaviour' in state (expected one of name, behavior, params)");
  }
  TEST_CASE("in transition") {
    check_edit("{from: tell, to: done, trigger: MessageSent}", "{from: tell, to: done, trigger: MessageSent, param: {}}",
               "param:", "unknown key 'param' in transition (expected one of from, to, trigger, params)");
  }
  TEST_CASE("in message") {
    check_edit("to: [robot2]}", "too: [robot2]}", "too", "unknown key 'too' in message (expected one of name, from, to)");
  }
  TEST_CASE("a behavior parameter") {
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5", "goal: [3.0, 1.0], dropof_m: 0.5", "dropof_m",
               "unknown parameter 'dropof_m' for behavior GoToGuarded (expected one of goal, dropoff_m, "
               "dead_zone_m, move_gain, avoid_gain, noise_gain, sphere_m, safety_margin_m, "
               "noise_persistence_cycles)");
  }
  TEST_CASE("a parameter of a behavior that takes none") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: Stop, params: {rate_deg_s: 1}}", "rate_deg_s",
               "unknown parameter 'rate_deg_s' for behavior Stop (it takes none)");
  }
  TEST_CASE("a trigger parameter") {
    check_edit("{from: tell, to: done, trigger: MessageSent}",
               "{from: tell, to: done, trigger: MessageSent, params: {msg: r1_done}}", "msg",
               "unknown parameter 'msg' for trigger MessageSent (expected one of message)");
  }
  TEST_CASE("a duplicate key") {
    check_edit("  rmax_m: 0.5\n", "  rmax_m: 0.5\n  rmax_m: 0.6\n", "rmax_m", "duplicate key 'rmax_m' in criteria (first at 5:3)",
               2);
  }
  TEST_CASE("a duplicate parameter") {
    check_edit("params: {radius_m: 0.2}}\n      - {from: tell", "params: {radius_m: 0.2, radius_m: 0.3}}\n      - {from: tell",
               "radius_m: 0.3", "duplicate parameter 'radius_m' for trigger AtGoal (first at 16:59)");
  }
}

TEST_SUITE("missing keys and parameters") {
  TEST_CASE("a missing top-level section") {
    const std::string text = replace_once(kRelay, "criteria:\n  tmax_s: 60\n  rmax_m: 0.5\n  threshold: 0.8\n", "");
    CHECK(error_of(text) == "t.yaml:1:1: missing required key 'criteria' at the top level");
  }
  TEST_CASE("a missing criterion") {
    check_edit("  threshold: 0.8\n", "", "tmax_s", "missing required key 'threshold' in criteria");
  }
  TEST_CASE("a robot without hal") {
    check_edit("    hal: tcp://127.0.0.1:8102\n", "", "name: robot2", "missing required key 'hal' in robot");
  }
  TEST_CASE("a state without behavior") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait}", "{name: wait}", "missing required key 'behavior' in state");
  }
  TEST_CASE("a transition without to") {
    check_edit("{from: tell, to: done, trigger: MessageSent}", "{from: tell, trigger: MessageSent}",
               "{from: tell", "missing required key 'to' in transition");
  }
  TEST_CASE("a GoToGuarded without goal") {
    check_edit("params: {goal: [3.0, 2.0], dropoff_m: 0.5}", "params: {dropoff_m: 0.5}", "{dropoff_m: 0.5}",
               "missing required parameter 'goal' for behavior GoToGuarded");
  }
  TEST_CASE("a GoToGuarded with no params at all: located at the behavior") {
    check_edit("behavior: GoToGuarded, params: {goal: [3.0, 2.0], dropoff_m: 0.5}", "behavior: GoToGuarded",
               "GoToGuarded", "missing required parameter 'goal' for behavior GoToGuarded", 2);
  }
  TEST_CASE("a Spin without rate") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: Spin, params: {}}", "{}",
               "missing required parameter 'rate_deg_s' for behavior Spin");
  }
  TEST_CASE("a Notify without message") {
    check_edit("behavior: Notify, params: {message: r1_done}", "behavior: Notify", "Notify",
               "missing required parameter 'message' for behavior Notify");
  }
  TEST_CASE("an AtGoal without radius") {
    check_edit("trigger: AtGoal, params: {radius_m: 0.2}}\n      - {from: tell", "trigger: AtGoal}\n      - {from: tell",
               "AtGoal", "missing required parameter 'radius_m' for trigger AtGoal");
  }
  TEST_CASE("an AtGoal out of a state that has no goal to default to") {
    check_edit("{from: wait, to: drive2, trigger: Notified, params: {message: r1_done}}",
               "{from: wait, to: drive2, trigger: AtGoal, params: {radius_m: 1}}", "{radius_m: 1}",
               "missing required parameter 'goal' for trigger AtGoal (source state 'wait' runs Stop, not "
               "GoToGuarded, so there is no goal to default to)");
  }
  TEST_CASE("a MessageSent out of a state that has no message to default to") {
    check_edit("{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
               "{from: drive2, to: finished, trigger: MessageSent}", "MessageSent",
               "missing required parameter 'message' for trigger MessageSent (source state 'drive2' runs "
               "GoToGuarded, not Notify, so there is no message to default to)", 2);
  }
  TEST_CASE("a Notified without message") {
    check_edit("trigger: Notified, params: {message: r1_done}", "trigger: Notified, params: {}", "{}",
               "missing required parameter 'message' for trigger Notified");
  }
  TEST_CASE("a HasTurned without angle") {
    check_edit("{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
               "{from: drive2, to: finished, trigger: HasTurned, params: {offset_deg: 1}}", "{offset_deg",
               "missing required parameter 'angle_deg' for trigger HasTurned");
  }
}

TEST_SUITE("unknown behavior, trigger and choices") {
  TEST_CASE("an unknown behavior") {
    check_edit("behavior: GoToGuarded, params: {goal: [3.0, 1.0]", "behavior: GoToGaurded, params: {goal: [3.0, 1.0]",
               "GoToGaurded", "unknown behavior 'GoToGaurded' (expected one of GoToGuarded, Spin, Stop, Notify)");
  }
  TEST_CASE("behavior names are case-sensitive") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: stop}", "stop}",
               "unknown behavior 'stop' (expected one of GoToGuarded, Spin, Stop, Notify)");
  }
  TEST_CASE("an unknown trigger") {
    check_edit("trigger: Notified", "trigger: Notifed", "Notifed",
               "unknown trigger 'Notifed' (expected one of AtGoal, HasTurned, Notified, MessageSent)");
  }
  TEST_CASE("an unknown abort action") {
    check_edit("  threshold: 0.8\n", "  threshold: 0.8\n  abort_action: abort\n", "abort\n",
               "unknown abort_action 'abort' (expected one of continue_and_warn, stop_and_notify)");
  }
}

TEST_SUITE("mistyped values") {
  TEST_CASE("a string where a number is expected") {
    check_edit("tmax_s: 60", "tmax_s: sixty", "sixty", "expected a number for 'tmax_s', got 'sixty'");
  }
  TEST_CASE("a quoted number is a string") {
    check_edit("tmax_s: 60", "tmax_s: \"60\"", "\"60\"", "expected a number for 'tmax_s', got the quoted string \"60\"");
  }
  TEST_CASE("an explicitly tagged number is a number, a !!str is not") {
    CHECK(error_of(replace_once(kRelay, "tmax_s: 60", "tmax_s: !!float 60")) == "no error");
    check_edit("tmax_s: 60", "tmax_s: !!str 60", "!!str",
               "expected a number for 'tmax_s', got '60' tagged tag:yaml.org,2002:str");
  }
  TEST_CASE("a number with trailing text") {
    check_edit("rmax_m: 0.5", "rmax_m: 0.5m", "0.5m", "expected a number for 'rmax_m', got '0.5m'");
  }
  TEST_CASE("a list where a number is expected") {
    check_edit("{radius_m: 0.2}}\n      - {from: tell", "{radius_m: [0.2]}}\n      - {from: tell", "[0.2]",
               "expected a number for 'radius_m', got a list");
  }
  TEST_CASE("null where a number is expected: located at the key") {
    check_edit("tmax_s: 60", "tmax_s:", "tmax_s", "expected a number for 'tmax_s', got null");
  }
  TEST_CASE("non-finite numbers") {
    check_edit("tmax_s: 60", "tmax_s: .inf", ".inf", "expected a number for 'tmax_s', got '.inf'");
    check_edit("tmax_s: 60", "tmax_s: nan", "nan", "expected a number for 'tmax_s', got 'nan'");
  }
  TEST_CASE("a goal with three coordinates") {
    check_edit("goal: [3.0, 1.0]", "goal: [3.0, 1.0, 0.0]", "[3.0, 1.0, 0.0]",
               "expected a list of 2 numbers [x_m, y_m] for 'goal', got 3 elements");
  }
  TEST_CASE("a goal with one coordinate") {
    check_edit("goal: [3.0, 1.0]", "goal: [3.0]", "[3.0]",
               "expected a list of 2 numbers [x_m, y_m] for 'goal', got 1 element");
  }
  TEST_CASE("a goal that is a mapping") {
    check_edit("goal: [3.0, 1.0]", "goal: {x_m: 3, y_m: 1}", "{x_m: 3, y_m: 1}",
               "expected a list of 2 numbers [x_m, y_m] for 'goal', got a mapping");
  }
  TEST_CASE("a goal coordinate that is not a number") {
    check_edit("goal: [3.0, 1.0]", "goal: [3.0, one]", "one", "expected a number for 'goal[1]', got 'one'");
  }
  TEST_CASE("a fraction where an integer is expected") {
    check_edit("dropoff_m: 0.5}}\n      - {name: tell", "dropoff_m: 0.5, noise_persistence_cycles: 2.5}}\n      - {name: tell",
               "2.5", "expected an integer for 'noise_persistence_cycles', got '2.5'");
  }
  TEST_CASE("a list where a name is expected") {
    check_edit("name: robot2", "name: [robot2]", "[robot2]", "expected a name for 'name', got a list");
  }
  TEST_CASE("a mapping where a string is expected") {
    check_edit("hal: tcp://127.0.0.1:8102", "hal: {url: x}", "{url: x}", "expected a string for 'hal', got a mapping");
  }
  TEST_CASE("a scalar where a list is expected") {
    check_edit("to: [robot2]", "to: robot2", "to: |robot2", "expected a list for 'to', got 'robot2'");
  }
  TEST_CASE("a list where a mapping is expected") {
    check_edit("{x_m: 1.0, y_m: 2.0}", "[1.0, 2.0]", "[1.0, 2.0]", "expected a mapping for 'start', got a list");
  }
  TEST_CASE("a state that is not a mapping") {
    check_edit("{name: wait, behavior: Stop}", "wait", "wait", "expected a mapping for each state, got 'wait'");
  }
  TEST_CASE("robots that are not a list") {
    const std::string text = "mission: {name: m}\ncriteria: {tmax_s: 1, rmax_m: 1, threshold: 1}\nrobots: {}\n";
    CHECK(error_of(text) == "t.yaml:3:9: expected a list for 'robots', got a mapping");
  }
}

TEST_SUITE("out-of-range values") {
  TEST_CASE("threshold above 1") {
    check_edit("threshold: 0.8", "threshold: 1.5", "1.5", "'threshold' out of range: 1.5 (expected 0 < threshold <= 1)");
  }
  TEST_CASE("threshold of 0") {
    check_edit("threshold: 0.8", "threshold: 0", "threshold: |0", "'threshold' out of range: 0 (expected 0 < threshold <= 1)");
  }
  TEST_CASE("a negative Tmax") {
    check_edit("tmax_s: 60", "tmax_s: -60", "-60", "'tmax_s' out of range: -60 (expected 0 < tmax_s <= 86400)");
  }
  TEST_CASE("an abort threshold above the launch threshold") {
    check_edit("  threshold: 0.8\n", "  threshold: 0.8\n  abort_threshold: 0.9\n", "0.9",
               "'abort_threshold' out of range: 0.9 (expected 0 <= abort_threshold <= 0.8)");
  }
  TEST_CASE("a zero success radius") {
    check_edit("{radius_m: 0.2}}\n      - {from: tell", "{radius_m: 0}}\n      - {from: tell", "0}}",
               "'radius_m' out of range: 0 (expected 0 < radius_m <= 1000)");
  }
  TEST_CASE("a negative gain") {
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5", "goal: [3.0, 1.0], dropoff_m: 0.5, avoid_gain: -1", "-1",
               "'avoid_gain' out of range: -1 (expected 0 <= avoid_gain <= 1000)");
  }
  TEST_CASE("a noise persistence of 0 cycles") {
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5", "goal: [3.0, 1.0], dropoff_m: 0.5, noise_persistence_cycles: 0",
               "0}}", "'noise_persistence_cycles' out of range: 0 (expected 1 <= noise_persistence_cycles <= 1000000)");
  }
  TEST_CASE("an integer too large for any type") {
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5",
               "goal: [3.0, 1.0], dropoff_m: 0.5, noise_persistence_cycles: 99999999999999999999999", "999",
               "'noise_persistence_cycles' out of range: 99999999999999999999999 (expected 1 <= "
               "noise_persistence_cycles <= 1000000)");
  }
  TEST_CASE("a zero obstacle sphere") {
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5", "goal: [3.0, 1.0], dropoff_m: 0.5, sphere_m: 0", "0}}",
               "'sphere_m' out of range: 0 (expected 0 < sphere_m <= 1000)");
  }
  TEST_CASE("a dropoff radius inside the dead zone") {
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5", "goal: [3.0, 1.0], dropoff_m: 0.01", "0.01",
               "'dropoff_m' (0.01) must not be less than 'dead_zone_m' (0.05)");
    check_edit("goal: [3.0, 1.0], dropoff_m: 0.5", "goal: [3.0, 1.0], dead_zone_m: 3", "3}}",
               "'dropoff_m' (2.5) must not be less than 'dead_zone_m' (3)");
  }
  TEST_CASE("a success radius inside the goal's dead zone") {
    check_edit("{radius_m: 0.2}}\n      - {from: tell", "{radius_m: 0.05}}\n      - {from: tell", "0.05",
               "'radius_m' (0.05) must exceed the source state's 'dead_zone_m' (0.05), or the robot may stop "
               "before it arrives");
  }
  TEST_CASE("a goal far off the map") {
    check_edit("goal: [3.0, 1.0]", "goal: [3.0, 1e5]", "1e5",
               "'goal[1]' out of range: 1e5 (expected -10000 <= goal[1] <= 10000)");
  }
  TEST_CASE("a robot goal far off the map") {
    check_edit("    hal: tcp://127.0.0.1:8102\n", "    goal: [-20000, 0]\n    hal: tcp://127.0.0.1:8102\n", "-20000",
               "'goal[0]' out of range: -20000 (expected -10000 <= goal[0] <= 10000)");
  }
  TEST_CASE("a start heading beyond a full turn") {
    check_edit("{x_m: 1.0, y_m: 1.0, theta_deg: 0}", "{x_m: 1.0, y_m: 1.0, theta_deg: 400}", "400",
               "'theta_deg' out of range: 400 (expected -360 <= theta_deg <= 360)");
  }
  TEST_CASE("a max speed of 0") {
    check_edit("    hal: tcp://127.0.0.1:8102\n", "    hal: tcp://127.0.0.1:8102\n    max_speed_mps: 0\n", "max_speed_mps: |0",
               "'max_speed_mps' out of range: 0 (expected 0 < max_speed_mps <= 2)");
  }
  TEST_CASE("a Spin rate of 0 or beyond a turn per second") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: Spin, params: {rate_deg_s: 0}}", "0}}",
               "'rate_deg_s' must not be 0 (a Spin that never turns; use Stop)");
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: Spin, params: {rate_deg_s: -400}}", "-400",
               "'rate_deg_s' out of range: -400 (expected -360 <= rate_deg_s <= 360)");
  }
  TEST_CASE("a HasTurned offset not below its angle") {
    check_edit("{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
               "{from: drive2, to: finished, trigger: HasTurned, params: {angle_deg: 90, offset_deg: 90}}", "90}",
               "'offset_deg' out of range: 90 (expected 0 <= offset_deg < 90)");
  }
  TEST_CASE("a HasTurned angle of 0") {
    check_edit("{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
               "{from: drive2, to: finished, trigger: HasTurned, params: {angle_deg: 0}}", "angle_deg: |0",
               "'angle_deg' out of range: 0 (expected 0 < angle_deg <= 3600)");
  }
}

TEST_SUITE("names and URLs") {
  TEST_CASE("a robot name with a space") {
    check_edit("name: robot2", "name: robot 2", "robot 2",
               "invalid robot name 'robot 2' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
  }
  TEST_CASE("a state name starting with a digit") {
    check_edit("{name: wait,", "{name: 1wait,", "1wait",
               "invalid state name '1wait' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
  }
  TEST_CASE("an invalid mission name") {
    check_edit("name: relay", "name: my-relay", "my-relay",
               "invalid mission name 'my-relay' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
  }
  TEST_CASE("a HAL URL without a scheme") {
    check_edit("hal: tcp://127.0.0.1:8102", "hal: 127.0.0.1:8102", "127.0.0.1:8102",
               "invalid URL '127.0.0.1:8102' for 'hal' (expected scheme://..., e.g. tcp://127.0.0.1:8101)");
  }
}

TEST_SUITE("FSA structure") {
  TEST_CASE("a transition from an unknown state") {
    check_edit("{from: tell, to: done", "{from: tel, to: done", "tel,",
               "transition from unknown state 'tel' (robot 'robot1' has states drive, tell, done)");
  }
  TEST_CASE("a transition to an unknown state") {
    check_edit("to: finished,", "to: finish,", "finish,",
               "transition to unknown state 'finish' (robot 'robot2' has states wait, drive2, finished)");
  }
  TEST_CASE("an unknown initial state") {
    check_edit("    hal: tcp://127.0.0.1:8102\n", "    hal: tcp://127.0.0.1:8102\n    initial: start\n", "start\n",
               "unknown initial state 'start' (robot 'robot2' has states wait, drive2, finished)");
  }
  TEST_CASE("an unreachable state") {
    check_edit("      - {name: finished, behavior: Stop}\n",
               "      - {name: finished, behavior: Stop}\n      - {name: orphan, behavior: Stop}\n", "orphan",
               "state 'orphan' of robot 'robot2' is unreachable from its initial state 'wait'");
  }
  TEST_CASE("a state unreachable because the initial state comes later") {
    check_edit("    hal: tcp://127.0.0.1:8102\n", "    hal: tcp://127.0.0.1:8102\n    initial: drive2\n", "wait,",
               "state 'wait' of robot 'robot2' is unreachable from its initial state 'drive2'");
  }
  TEST_CASE("a robot whose FSA can never finish") {
    check_edit("{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
               "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}\n"
               "      - {from: finished, to: wait, trigger: HasTurned, params: {angle_deg: 10}}",
               "transitions", "robot 'robot2' has no final state (a state with no outgoing transitions), so its FSA "
                              "can never finish", 2);
  }
  TEST_CASE("a robot with no states") {
    const std::string text = "mission: {name: m}\ncriteria: {tmax_s: 1, rmax_m: 1, threshold: 1}\n"
                             "robots:\n  - {name: r, start: {x_m: 0, y_m: 0}, hal: \"memq://\", states: []}\n";
    CHECK(error_of(text) == "t.yaml:" + loc(text, "[]") + ": robot 'r' has no states");
  }
  TEST_CASE("no robots") {
    const std::string text = "mission: {name: m}\ncriteria: {tmax_s: 1, rmax_m: 1, threshold: 1}\nrobots: []\n";
    CHECK(error_of(text) == "t.yaml:3:9: no robots (expected at least one)");
  }
}

TEST_SUITE("duplicate names") {
  TEST_CASE("a duplicate robot name") {
    check_edit("name: robot2", "name: robot1", "robot1", "duplicate robot name 'robot1' (first at 8:11)", 2);
  }
  TEST_CASE("a duplicate state name") {
    check_edit("{name: finished, behavior: Stop}", "{name: wait, behavior: Stop}", "wait", "duplicate state name 'wait' in robot 'robot2' (first at 22:16)", 2);
  }
  TEST_CASE("a duplicate message name") {
    const std::string text = std::string(kRelay) + "  - {name: r1_done, from: robot1, to: [robot2]}\n";
    CHECK(error_of(text) == "t.yaml:" + loc(text, "r1_done", 4) + ": duplicate message name 'r1_done' (first at " +
                                loc(text, "r1_done", 3) + ")");
  }
}

TEST_SUITE("echoed text") {
  TEST_CASE("control and non-ASCII bytes are escaped and long text is cut") {
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: \"St\\top\\u00e9\"}", "\"St",
               "unknown behavior 'St\\x09op\\xc3\\xa9' (expected one of GoToGuarded, Spin, Stop, Notify)");
    const std::string long_name(60, 'x');
    check_edit("{name: wait, behavior: Stop}", "{name: wait, behavior: " + long_name + "}", long_name,
               "unknown behavior '" + std::string(48, 'x') + "...' (expected one of GoToGuarded, Spin, Stop, Notify)");
  }
}
