// Where the team is, as one robot knows it, and the snapshot handed to the
// verifier: states, entry times, odometric path and rotation, messages.
#include <doctest/doctest.h>

#include <cmath>

#include "fake_team_link.hpp"
#include "gate_test_util.hpp"
#include "p3at/launch_gate/team_progress.hpp"

using namespace p3at;

namespace {
hal::Telemetry telemetry(const std::string& robot, const std::string& state, double x, double y, double th,
                         std::uint64_t cycles) {
  hal::Telemetry t;
  t.robot = robot;
  t.state = state;
  t.x_m = x;
  t.y_m = y;
  t.theta_rad = th;
  t.cycles = cycles;
  return t;
}
}  // namespace

TEST_CASE("before anything is heard, every robot is at its start, in its initial state, at time 0") {
  const auto m = test::relay_mission();
  gate::TeamProgress progress(m, 1);
  test::FakeTeamLink link("robot2");
  exec::MessageBook book(m.messages.size());
  const auto s = progress.snapshot(0.0, book, link);
  REQUIRE(s.robots.size() == 2);
  CHECK(s.robots[0].state == 0);
  CHECK(s.robots[0].x_m == doctest::Approx(1.0));
  CHECK(s.robots[1].y_m == doctest::Approx(3.0));
  CHECK(s.robots[1].travelled_m == 0.0);
  CHECK_FALSE(s.robots[0].finished);
  CHECK(s.messages_sent == std::vector<bool>{false});
  CHECK(s.messages_received == std::vector<bool>{false});
  CHECK_FALSE(progress.robot(0).heard);
  CHECK(progress.robot(1).heard);
}

TEST_CASE("own progress: path length, absolute rotation, state entry time") {
  const auto m = test::relay_mission();
  gate::TeamProgress progress(m, 0);
  progress.observe_self(0.1, 0, {1.3, 1.0, 0.0}, false);
  progress.observe_self(0.2, 0, {1.3, 1.4, 0.5}, false);
  progress.observe_self(0.3, 0, {1.3, 1.4, -0.5}, false);
  progress.observe_self(4.2, 1, {1.3, 1.4, -0.5}, false);
  const auto& r = progress.robot(0);
  CHECK(r.travelled_m == doctest::Approx(0.7));
  CHECK(r.turned_rad == doctest::Approx(1.5));
  CHECK(r.state == 1);
  CHECK(r.entered_s == doctest::Approx(4.2));
  CHECK(r.visited == std::vector<bool>{true, true, false});
}

TEST_CASE("teammates from telemetry: each sample used once, unknown states ignored, finished from status") {
  const auto m = test::relay_mission();
  gate::TeamProgress progress(m, 0);
  progress.observe_teammates(1.0, {telemetry("robot2", "wait", 1.0, 3.0, 0.0, 10)}, {});
  progress.observe_teammates(2.0, {telemetry("robot2", "drive", 1.5, 3.0, 0.0, 20)}, {});
  progress.observe_teammates(2.1, {telemetry("robot2", "drive", 1.5, 3.0, 0.0, 20)}, {});  // the same sample again
  progress.observe_teammates(2.2, {telemetry("robot2", "no-such-state", 9.0, 9.0, 0.0, 21)}, {});
  progress.observe_teammates(2.3, {telemetry("robot7", "drive", 9.0, 9.0, 0.0, 22)}, {});
  const auto& r = progress.robot(1);
  CHECK(r.heard);
  CHECK(r.state == 1);
  CHECK(r.entered_s == doctest::Approx(2.0));
  CHECK(r.travelled_m == doctest::Approx(0.5));
  CHECK(r.x_m == doctest::Approx(1.5));
  CHECK_FALSE(r.finished);
  progress.observe_teammates(9.0, {}, {hal::TeamStatus{"robot2", "finished", "done", "", 0.9}});
  CHECK(progress.robot(1).finished);
}

TEST_CASE("messages: own sent and acknowledged; received by the only recipient; between others by the sender's states") {
  const auto m = test::relay_mission();
  test::FakeTeamLink link1("robot1");
  test::FakeTeamLink link2("robot2");
  test::FakeTeamLink::connect(link1, link2);
  link1.auto_ack = false;
  link2.auto_ack = false;

  // robot1's view: it sent r1_done; received once robot2 acknowledged.
  gate::TeamProgress p1(m, 0);
  exec::MessageBook book1(m.messages.size());
  auto seq = link1.notify("r1_done", {"robot2"});
  REQUIRE(seq.ok());
  book1.record_sent(0, *seq);
  auto s = p1.snapshot(5.0, book1, link1);
  CHECK(s.messages_sent[0]);
  CHECK_FALSE(s.messages_received[0]);
  link1.ack(*seq, "robot2");
  s = p1.snapshot(5.1, book1, link1);
  CHECK(s.messages_received[0]);
  CHECK(s.elapsed_s == doctest::Approx(5.1));

  // robot2's view: it received the message, and is its only recipient.
  gate::TeamProgress p2(m, 1);
  exec::MessageBook book2(m.messages.size());
  CHECK_FALSE(p2.snapshot(5.0, book2, link2).messages_sent[0]);
  book2.mark_received(0);
  s = p2.snapshot(5.0, book2, link2);
  CHECK(s.messages_sent[0]);
  CHECK(s.messages_received[0]);

  // A third view (robot2's progress, message unknown to its book): the sender seen in "tell", then leaving it.
  gate::TeamProgress p3(m, 1);
  exec::MessageBook empty(m.messages.size());
  p3.observe_teammates(4.0, {telemetry("robot1", "tell", 3.0, 1.0, 0.0, 40)}, {});
  s = p3.snapshot(4.0, empty, link2);
  CHECK(s.messages_sent[0]);
  CHECK_FALSE(s.messages_received[0]);
  p3.observe_teammates(4.3, {telemetry("robot1", "done", 3.0, 1.0, 0.0, 43)}, {});
  s = p3.snapshot(4.3, empty, link2);
  CHECK(s.messages_received[0]);
  CHECK(s.robots[0].finished);  // "done" is final
}
