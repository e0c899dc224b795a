// The team's messages: every Notify and Notified must match a declared
// message with the right sender and recipients, and every declared sender sends.

#include <doctest/doctest.h>

#include "fixtures.hpp"

using namespace p3at::mission;
using p3at::mission::test::error_of;
using p3at::mission::test::kBoundingOverwatch;
using p3at::mission::test::kRelay;
using p3at::mission::test::loc;
using p3at::mission::test::replace_once;

namespace {

void check_edit(std::string_view from, std::string_view to, std::string_view at, const std::string& detail,
                int nth = 1) {
  const std::string text = replace_once(kRelay, from, to);
  CHECK(error_of(text) == "t.yaml:" + loc(text, at, nth) + ": " + detail);
}

}  // namespace

TEST_CASE("a Notified on a message that is not declared") {
  check_edit("trigger: Notified, params: {message: r1_done}", "trigger: Notified, params: {message: r1_gone}", "r1_gone",
             "Notified on message 'r1_gone' that no teammate ever sends (it is not listed in messages)");
}

TEST_CASE("a Notified on a message sent to other robots only") {
  std::string text = replace_once(kRelay, "  - name: robot2\n",
                                  "  - name: robot3\n    start: {x_m: 0, y_m: 0}\n    hal: tcp://127.0.0.1:8103\n"
                                  "    states: [{name: idle, behavior: Stop}]\n  - name: robot2\n");
  text = replace_once(text, "to: [robot2]", "to: [robot3]");
  CHECK(error_of(text) == "t.yaml:" + loc(text, "message: |r1_done}}\n      - {from: drive2") +
                              ": Notified on message 'r1_done' that no teammate ever sends to robot 'robot2' "
                              "(messages lists its recipients as robot3)");
}

TEST_CASE("a Notified on a robot's own message") {
  // robot1 waits for the message it sends itself: no teammate sends it.
  std::string text = replace_once(kRelay, "{from: tell, to: done, trigger: MessageSent}",
                                  "{from: tell, to: done, trigger: Notified, params: {message: r1_done}}");
  CHECK(error_of(text) == "t.yaml:" + loc(text, "r1_done", 2) +
                              ": Notified on message 'r1_done' that no teammate ever sends (robot 'robot1' is its "
                              "own sender)");
}

TEST_CASE("a Notify of a message that is not declared") {
  std::string text = replace_once(kRelay, "{message: r1_done}}\n      - {name: done", "{message: r1_other}}\n      - {name: done");
  CHECK(error_of(text) == "t.yaml:" + loc(text, "r1_other") +
                              ": message 'r1_other' is not listed in messages (each message needs its sender and "
                              "recipients there)");
}

TEST_CASE("a Notify by a robot the message does not name as its sender") {
  std::string text = replace_once(kRelay, "      - {name: finished, behavior: Stop}\n",
                                  "      - {name: finished, behavior: Notify, params: {message: r1_done}}\n"
                                  "      - {name: end, behavior: Stop}\n");
  text = replace_once(text, "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}",
                      "{from: drive2, to: finished, trigger: AtGoal, params: {radius_m: 0.2}}\n"
                      "      - {from: finished, to: end, trigger: MessageSent}");
  CHECK(error_of(text) == "t.yaml:" + loc(text, "finished, behavior: Notify, params: {message: |r1_done") +
                              ": robot 'robot2' sends message 'r1_done', but messages lists robot 'robot1' as its "
                              "sender");
}

TEST_CASE("a declared message whose sender never sends it") {
  const std::string text = std::string(kRelay) + "  - {name: r2_done, from: robot2, to: [robot1]}\n";
  CHECK(error_of(text) == "t.yaml:" + loc(text, "from: |robot2") +
                              ": message 'r2_done' is listed as sent by robot 'robot2', which has no Notify state "
                              "for it");
}

TEST_CASE("a MessageSent on a message the robot never sends") {
  check_edit("{from: tell, to: done, trigger: MessageSent}",
             "{from: tell, to: done, trigger: MessageSent, params: {message: r2_done}}", "r2_done",
             "MessageSent on message 'r2_done' that robot 'robot1' never sends (it has no Notify state for it)");
}

TEST_CASE("a message from or to an unknown robot") {
  check_edit("from: robot1, to: [robot2]", "from: robot9, to: [robot2]", "robot9",
             "unknown robot 'robot9' (expected one of robot1, robot2)");
  check_edit("from: robot1, to: [robot2]", "from: robot1, to: [robot2, robo3]", "robo3",
             "unknown robot 'robo3' (expected one of robot1, robot2)");
  check_edit("from: robot1, to: [robot2]", "from: robot1, to: [[robot2]]", "[robot2]]",
             "expected a robot name for 'to', got a list");
}

TEST_CASE("a message with no recipients, a repeated one, or its sender among them") {
  check_edit("to: [robot2]", "to: []", "[]", "message 'r1_done' has no recipients");
  check_edit("to: [robot2]", "to: [robot2, robot2]", "robot2, |robot2",
             "duplicate recipient 'robot2' of message 'r1_done' (first at " +
                 loc(replace_once(kRelay, "to: [robot2]", "to: [robot2, robot2]"), "to: [|robot2") + ")");
  check_edit("to: [robot2]", "to: [robot2, robot1]", "robot2, |robot1",
             "message 'r1_done' lists its sender 'robot1' as a recipient");
}

TEST_CASE("a recipient that never listens and an explicit MessageSent are fine") {
  std::string text = replace_once(kRelay, "  - name: robot2\n",
                                  "  - name: robot3\n    start: {x_m: 0, y_m: 0}\n    hal: tcp://127.0.0.1:8103\n"
                                  "    states: [{name: idle, behavior: Stop}]\n  - name: robot2\n");
  text = replace_once(text, "to: [robot2]", "to: [robot3, robot2]");
  text = replace_once(text, "{from: tell, to: done, trigger: MessageSent}",
                      "{from: tell, to: done, trigger: MessageSent, params: {message: r1_done}}");
  const Mission m = parse_mission(text, "t.yaml");
  REQUIRE(m.messages.size() == 1);
  CHECK(m.messages[0].to == std::vector<std::size_t>{1, 2});
  CHECK(std::get<MessageSentParams>(m.robots[0].transitions[1].trigger).message == "r1_done");
}

TEST_CASE("the Bounding Overwatch fixture fails if one of its notifications is dropped") {
  // Removing robot2's second Notify leaves r2_at_c declared but never sent.
  std::string text = replace_once(kBoundingOverwatch, "{name: tell_c, behavior: Notify, params: {message: r2_at_c}}",
                                  "{name: tell_c, behavior: Stop}");
  text = replace_once(text, "{from: tell_c, to: wait_d, trigger: MessageSent}",
                      "{from: tell_c, to: wait_d, trigger: HasTurned, params: {angle_deg: 1}}");
  CHECK(error_of(text) == "t.yaml:" + loc(text, "r2_at_c, from: |robot2") +
                              ": message 'r2_at_c' is listed as sent by robot 'robot2', which has no Notify state "
                              "for it");
}
