// The gate session against the fake team link and a manual clock: it
// publishes and republishes the verdict, decides as soon as the team agrees,
// times out on a silent teammate, lingers after a refusal so teammates hear
// it, keeps notifications that arrive meanwhile, and stops on request.
#include <doctest/doctest.h>

#include <atomic>

#include "fake_clock.hpp"
#include "fake_team_link.hpp"
#include "gate_test_util.hpp"
#include "p3at/launch_gate/gate_session.hpp"

using namespace p3at;
using gate::AgreementState;
using gate::GateDecision;

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
}  // namespace

TEST_CASE("a teammate that already said GO: launch at once, own verdict published") {
  test::FakeClock clock;
  test::FakeTeamLink link("robot1");
  link.set_teammate_verdict(test::verdict("robot2", GateDecision::go));
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::launch);
  CHECK_FALSE(r.interrupted);
  CHECK(r.waited_us == 0);
  REQUIRE(link.verdicts_sent.size() == 1);
  CHECK(link.verdicts_sent[0].decision == GateDecision::go);
  CHECK(link.poll_calls >= 1);
}

TEST_CASE("a teammate heard after 1.2 s: republished every 200 ms meanwhile, launch then") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  const auto pace = [&](std::int64_t deadline_us) {
    clock.sleep_until_us(deadline_us);
    if (clock.now_us() >= 1'200'000) link.set_teammate_verdict(test::verdict("robot2", GateDecision::override_go));
  };
  const auto r =
      gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options(), pace);
  CHECK(r.agreement.state == AgreementState::launch);
  CHECK(r.waited_us == 1'200'000);
  // Published at 0, 0.2, …, 1.2 s: seven times.
  CHECK(r.verdicts_published == 7);
  CHECK(link.verdicts_sent.size() == 7);
}

TEST_CASE("a silent teammate: refused after the timeout, having lingered to publish") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  const auto r = gate::run_gate_session(link, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::silent);
  CHECK(r.agreement.silent == std::vector<std::string>{"robot2"});
  CHECK(r.waited_us == 3'000'000);
  // 3 s at 5 Hz plus the 1 s linger: about 20 publications, never motion.
  CHECK(r.verdicts_published >= 19);
  CHECK(r.verdicts_published <= 21);
  CHECK(clock.now_us() == 4'000'000);
}

TEST_CASE("own NO-GO with the teammate heard: refused at once, the verdict keeps going out for the linger") {
  test::FakeClock clock(0);
  test::FakeTeamLink link("robot1");
  link.set_teammate_verdict(test::verdict("robot2", GateDecision::go));
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
    if (clock.now_us() >= 2'000'000) link.set_teammate_verdict(test::verdict("robot2", GateDecision::go));
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
  link.set_teammate_verdict(test::verdict("robot2", GateDecision::go, test::kHashB));
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

TEST_CASE("two robots on connected fake links agree: each sees the other's GO") {
  test::FakeClock clock(0);
  test::FakeTeamLink a("robot1");
  test::FakeTeamLink b("robot2");
  test::FakeTeamLink::connect(a, b);
  // robot2's session first publishes its GO; robot1's then launches at once.
  b.set_teammate_verdict(test::verdict("robot1", GateDecision::go));
  CHECK(gate::run_gate_session(b, clock, test::verdict("robot2", GateDecision::go), kTeam, options()).agreement.state ==
        AgreementState::launch);
  const auto r = gate::run_gate_session(a, clock, test::verdict("robot1", GateDecision::go), kTeam, options());
  CHECK(r.agreement.state == AgreementState::launch);
  REQUIRE(r.agreement.team.size() == 2);
  CHECK(r.agreement.team[1].robot == "robot2");
}
