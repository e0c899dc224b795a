// The gate session against the fake team link and a manual clock: it
// publishes and republishes the verdict, commits (setting the link's session)
// once every teammate has heard this gate, launches on their commitments,
// times out on a silent teammate, lingers after a refusal so teammates hear
// it (publishing NO-GO, never the earlier GO), keeps notifications that
// arrive meanwhile, and stops on request.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>

#include "fake_clock.hpp"
#include "fake_team_link.hpp"
#include "gate_test_util.hpp"
#include "p3at/launch_gate/gate_session.hpp"
#include "p3at/launch_gate/launch_session.hpp"

using namespace p3at;
using gate::AgreementState;
using hal::GateDecision;

namespace {
const std::vector<std::string> kTeam{"robot1", "robot2"};

gate::SessionOptions options(std::int64_t timeout_us = 3'000'000) {
  gate::SessionOptions o;
  o.timeout_us = timeout_us;
  o.republish_us = 200'000;
  o.step_us = 50'000;
  o.refusal_linger_us = 1'000'000;
  return o;
}

const std::string kSession =
    gate::launch_session_id(test::kHashA, {{"robot1", test::nonce_of("robot1")}, {"robot2", test::nonce_of("robot2")}});

/// robot2's GO having heard robot1's gate; committed to the pair's session if asked.
hal::GateVerdict robot2_go(bool commit = true, GateDecision d = GateDecision::go) {
  hal::GateVerdict v = test::hearing(test::verdict("robot2", d), "robot1");
  if (commit) v.session = kSession;
  return v;
}
}  // namespace

TEST_CASE("a teammate that already committed to this gate: commit and launch at once, GO with the session published") {
  test::FakeClock clock;
  test::FakeTeamLink link("robot1");
  link.set_teammate_verdict(robot2_go());
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::launch);
  CHECK_FALSE(r.interrupted);
  CHECK(r.waited_us == 0);
  REQUIRE(link.verdicts_sent.size() == 1);
  CHECK(link.verdicts_sent[0].decision == GateDecision::go);
  CHECK(link.verdicts_sent[0].session == kSession);
  CHECK(link.verdicts_sent[0].heard == std::vector<hal::HeardNonce>{{"robot2", test::nonce_of("robot2")}});
  CHECK(r.published.session == kSession);  // what the mission goes on publishing
  CHECK(link.session() == kSession);      // the link now speaks only in this session
  CHECK(link.poll_calls >= 1);
}

TEST_CASE("a teammate's GO from another gate (not echoing our nonce) never launches: silent, NO-GO published after") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.set_teammate_verdict(test::committed(test::hearing(test::verdict("robot2", GateDecision::go), "robot1", 4),
                                            kSession));
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::silent);
  CHECK(link.session().empty());
  CHECK(link.verdicts_sent.front().decision == GateDecision::go);
  // From the refusal on, only NO-GO goes out.
  const auto first_no_go = std::find_if(link.verdicts_sent.begin(), link.verdicts_sent.end(),
                                        [](const hal::GateVerdict& v) { return v.decision == GateDecision::no_go; });
  REQUIRE(first_no_go != link.verdicts_sent.end());
  CHECK(std::all_of(first_no_go, link.verdicts_sent.end(),
                    [](const hal::GateVerdict& v) { return v.decision == GateDecision::no_go && v.session.empty(); }));
}

TEST_CASE("a teammate heard after 1.2 s: republished every 200 ms meanwhile, launch then") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  const auto pace = [&](std::int64_t deadline_us) {
    clock.sleep_until_us(deadline_us);
    if (clock.now_us() >= 1'200'000) link.set_teammate_verdict(robot2_go(true, GateDecision::override_go));
  };
  const auto r =
      gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options(), pace);
  CHECK(r.agreement.state == AgreementState::launch);
  CHECK(r.waited_us == 1'200'000);
  // Published at 0, 0.2, …, 1.2 s: seven times; the last with the session.
  CHECK(r.verdicts_published == 7);
  REQUIRE(link.verdicts_sent.size() == 7);
  CHECK(link.verdicts_sent[5].session.empty());
  CHECK(link.verdicts_sent[6].session == kSession);
}

TEST_CASE("a silent teammate: refused after the timeout, having lingered to publish") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::silent);
  CHECK(r.agreement.silent == std::vector<std::string>{"robot2"});
  CHECK(r.waited_us == 3'000'000);
  // 3 s at 5 Hz plus the 1 s linger: about 20 publications, never motion;
  // the refusal is published at once, and from then on only NO-GO.
  CHECK(r.verdicts_published >= 19);
  CHECK(r.verdicts_published <= 22);
  CHECK(clock.now_us() == 4'000'000);
  CHECK(link.verdicts_sent.back().decision == GateDecision::no_go);
  CHECK(link.verdicts_sent.back().detail.find("refused: no verdict from robot2") == 0);
}

TEST_CASE("own NO-GO with the teammate heard: refused at once, the verdict keeps going out for the linger") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.set_teammate_verdict(robot2_go(false));
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::no_go, test::kHashA, 0.2),
                                        kTeam, options());
  CHECK(r.agreement.state == AgreementState::no_go);
  CHECK(r.waited_us == 0);
  CHECK(clock.now_us() == 1'000'000);
  CHECK(r.verdicts_published == 6);  // 0, 0.2, 0.4, 0.6, 0.8, 1.0 s
  for (const auto& v : link.verdicts_sent) CHECK(v.decision == GateDecision::no_go);
}

TEST_CASE("own NO-GO with a teammate not heard yet: it keeps telling until the teammate shows up") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  const auto pace = [&](std::int64_t deadline_us) {
    clock.sleep_until_us(deadline_us);
    if (clock.now_us() >= 2'000'000) link.set_teammate_verdict(robot2_go(false));
  };
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::no_go), kTeam, options(),
                                        pace);
  CHECK(r.agreement.state == AgreementState::no_go);
  CHECK(clock.now_us() == 2'000'000);  // heard at 2 s (past the 1 s minimum): done
  CHECK(r.verdicts_published == 11);   // every 200 ms from 0 to 2 s

  // Nobody ever shows up: it stops at the gate's timeout (3 s from the start).
  test::FakeClock clock2(0);
  test::FakeTeamLink alone("robot1");
  const auto r2 = gate::run_gate_session(alone, clock2, test::verdict("robot1", GateDecision::no_go), kTeam, options());
  CHECK(r2.agreement.state == AgreementState::no_go);
  CHECK(clock2.now_us() == 3'000'000);
}

TEST_CASE("a mismatched teammate hash refuses; notifications received meanwhile are kept for the executive") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.deliver("robot2", "r2_ready", 4);
  link.set_teammate_verdict(test::hearing(test::verdict("robot2", GateDecision::go, test::kHashB), "robot1"));
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::mismatch);
  REQUIRE(r.early.size() == 1);
  CHECK(r.early[0].message == "r2_ready");
  CHECK(r.early[0].seq == 4);
}

TEST_CASE("a stop request ends the session undecided; a failing publish does not stop it") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.fail_publish_verdict = true;
  std::atomic<bool> stop{false};
  const auto pace = [&](std::int64_t deadline_us) {
    clock.sleep_until_us(deadline_us);
    if (clock.now_us() >= 500'000) stop = true;
  };
  const auto r =
      gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options(), pace, &stop);
  CHECK(r.interrupted);
  CHECK(r.agreement.state == AgreementState::waiting);
  CHECK(r.verdicts_published == 0);
  CHECK(clock.now_us() == 500'000);  // no linger after an interruption
}

TEST_CASE("interrupted before committing: one NO-GO tells the team; after committing: nothing more is said") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  std::atomic<bool> stop{false};
  const auto pace = [&](std::int64_t deadline_us) {
    clock.sleep_until_us(deadline_us);
    if (clock.now_us() >= 500'000) stop = true;
  };
  const auto r =
      gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options(), pace, &stop);
  CHECK(r.interrupted);
  CHECK(link.verdicts_sent.back().decision == GateDecision::no_go);

  test::FakeClock clock2(0);
  test::FakeTeamLink committed_link("robot1");
  committed_link.set_teammate_verdict(robot2_go(false));  // heard, not committed: robot1 commits and waits
  std::atomic<bool> stop2{false};
  const auto pace2 = [&](std::int64_t deadline_us) {
    clock2.sleep_until_us(deadline_us);
    if (clock2.now_us() >= 500'000) stop2 = true;
  };
  const auto r2 = gate::run_gate_session(committed_link, clock2, test::verdict("robot1", GateDecision::go), kTeam,
                                         options(), pace2, &stop2);
  CHECK(r2.interrupted);
  CHECK(r2.agreement.committed);
  for (const auto& v : committed_link.verdicts_sent) CHECK(v.decision == GateDecision::go);
}

TEST_CASE("committed but the teammate's commitment never comes: in doubt after timeout + doubt, nothing refused") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.set_teammate_verdict(robot2_go(false));
  auto o = options();
  o.doubt_us = 2'000'000;
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, o);
  CHECK(r.agreement.state == AgreementState::in_doubt);
  CHECK(r.waited_us == 5'000'000);
  CHECK(clock.now_us() == 5'000'000);  // no linger: it says nothing that could stop a teammate that launched
  for (const auto& v : link.verdicts_sent) CHECK(v.decision == GateDecision::go);
}

TEST_CASE("silent with bad tags counted: the refusal says wrong team key?") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.stats_for_test().rejected_bad_tag = 25;
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::silent);
  CHECK(r.agreement.reason.find("25 team messages failed authentication (rejected_bad_tag): wrong team key?") !=
        std::string::npos);
}

TEST_CASE("two robots on connected fake links, one after the other: the first commits, the second launches, then the first") {
  test::FakeClock clock(0);
  test::FakeTeamLink a("robot1");
  test::FakeTeamLink b("robot2");
  test::FakeTeamLink::connect(a, b);
  // robot1 alone publishes its GO and gives up after 1 s (silent): NO-GO goes out.
  auto o = options(1'000'000);
  o.refusal_linger_us = 0;
  CHECK(gate::run_gate_session(a, clock, test::verdict("robot1", GateDecision::go), kTeam, o).agreement.state ==
        AgreementState::silent);
  // robot2, started later, hears robot1's refusal (but it does not echo robot2's
  // gate): it never launches on it, and never on the GO robot1 published earlier.
  const auto r = gate::run_gate_session(b, clock, test::verdict("robot2", GateDecision::go), kTeam, o);
  CHECK(r.agreement.state == AgreementState::silent);
  CHECK(b.teammate_verdicts().front().decision == GateDecision::no_go);
}
