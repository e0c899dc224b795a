// The team link the executive gets during the mission: wall time for the real
// link whatever time it is given, early notifications first, the verdict
// republished, status stamped with the re-verified probability and note.
#include <doctest/doctest.h>

#include <type_traits>

#include "fake_clock.hpp"
#include "fake_team_link.hpp"
#include "gate_test_util.hpp"
#include "p3at/launch_gate/gate_team_link.hpp"

using namespace p3at;

TEST_CASE("poll: the real link runs on the link clock; notifications held over from the gate come first") {
  test::FakeClock wall(5'000'000);
  test::FakeTeamLink inner("robot2");
  gate::GateTeamLink link(inner, wall);
  inner.deliver("robot1", "later", 9);
  link.hand_over({hal::TeamNotification{"robot1", "r1_done", 3}});
  int hooks = 0;
  link.after_poll = [&] { ++hooks; };
  std::vector<hal::TeamNotification> got;
  REQUIRE(link.poll(42, got).ok());  // mission time 42 µs: ignored for the real link
  CHECK(inner.last_poll_us == 5'000'000);
  REQUIRE(got.size() == 2);
  CHECK(got[0].message == "r1_done");
  CHECK(got[1].message == "later");
  CHECK(hooks == 1);
  got.clear();
  REQUIRE(link.poll(43, got).ok());
  CHECK(got.empty());  // handed over once only
  CHECK(hooks == 2);
}

TEST_CASE("the verdict is republished every interval of link time once kept") {
  test::FakeClock wall(0);
  test::FakeTeamLink inner("robot1");
  gate::GateTeamLink link(inner, wall);
  std::vector<hal::TeamNotification> got;
  REQUIRE(link.poll(0, got).ok());
  CHECK(inner.verdicts_sent.empty());
  link.keep_publishing(test::verdict("robot1", gate::GateDecision::go), 500'000);
  for (int i = 0; i < 21; ++i) {  // 0 .. 2.0 s in 100 ms steps
    REQUIRE(link.poll(0, got).ok());
    wall.advance_us(100'000);
  }
  CHECK(inner.verdicts_sent.size() == 5);  // 0, 0.5, 1.0, 1.5, 2.0 s
  CHECK(link.verdicts_republished() == 5);
}

TEST_CASE("status carries the re-verified probability and, while running, the note; set_p_success republishes") {
  test::FakeClock wall;
  test::FakeTeamLink inner("robot1");
  gate::GateTeamLink link(inner, wall);
  REQUIRE(link.publish_status({"robot1", "running", "drive", "", 0.91}).ok());
  CHECK(inner.status_sent.back().p_success == doctest::Approx(0.91));  // the executive's own value until told
  link.set_note("warning: low");
  link.set_p_success(0.42);
  REQUIRE(inner.status_sent.size() == 2);
  CHECK(inner.status_sent.back().p_success == doctest::Approx(0.42));
  CHECK(inner.status_sent.back().reason == "warning: low");
  CHECK(inner.status_sent.back().state == "drive");
  REQUIRE(link.publish_status({"robot1", "aborted", "drive", "teammate aborted", 0.91}).ok());
  CHECK(inner.status_sent.back().reason == "teammate aborted");  // a real reason is never replaced
  CHECK(inner.status_sent.back().p_success == doctest::Approx(0.42));
}

TEST_CASE("everything else is forwarded") {
  test::FakeClock wall;
  test::FakeTeamLink inner("robot1");
  test::FakeTeamLink peer("robot2");
  test::FakeTeamLink::connect(inner, peer);
  gate::GateTeamLink link(inner, wall);
  auto seq = link.notify("r1_done", {"robot2"});
  REQUIRE(seq.ok());
  CHECK(inner.notify_calls.size() == 1);
  std::vector<hal::TeamNotification> got;
  REQUIRE(peer.poll(0, got).ok());  // auto-acknowledges
  CHECK(link.acknowledged(*seq));
  // Verdicts are the gate's, on the inner VerdictLink: the executive's link has none.
  static_assert(!std::is_base_of_v<gate::VerdictLink, gate::GateTeamLink>);
  REQUIRE(peer.publish_verdict(test::verdict("robot2", gate::GateDecision::go)).ok());
  CHECK(inner.teammate_verdicts().size() == 1);
  REQUIRE(peer.publish_telemetry(hal::Telemetry{}).ok());
  CHECK(link.teammate_telemetry().size() == 1);
  REQUIRE(peer.publish_status({"robot2", "running", "wait", "", -1.0}).ok());
  CHECK(link.teammate_status().size() == 1);
  REQUIRE(link.publish_telemetry(hal::Telemetry{}).ok());
  CHECK(inner.telemetry_sent.size() == 1);
  CHECK(&link.stats() == &inner.stats());
}
