// The team agreement (docs/launch-gate.md, "The launch as an agreement"): a
// verdict counts only when it echoes this gate's nonce, a robot commits to a
// session made of every robot's nonce, launches only on every teammate's
// commitment to that same session, never publishes GO after refusing, and
// never refuses by timeout once committed. Then the property itself, over
// thousands of randomised runs of whole teams with lost and late messages:
// whenever any robot refused, no robot launched.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>

#include "gate_test_util.hpp"
#include "p3at/hal/team_wire.hpp"
#include "p3at/launch_gate/launch_session.hpp"
#include "p3at/launch_gate/team_agreement.hpp"

using namespace p3at;
using gate::AgreementState;
using hal::GateDecision;
using test::committed;
using test::hearing;
using test::nonce_of;

namespace {
const std::vector<std::string> kTeam{"robot1", "robot2", "robot3"};
constexpr std::int64_t kTimeout = 5'000'000;
constexpr std::int64_t kDoubt = 2'000'000;

gate::TeamAgreement make(GateDecision own = GateDecision::go) {
  return gate::TeamAgreement(test::verdict("robot1", own), kTeam, 1'000'000, kTimeout, kDoubt);
}

/// A teammate's GO that has heard robot1's gate.
hal::GateVerdict current_go(const std::string& robot, GateDecision d = GateDecision::go) {
  return hearing(test::verdict(robot, d), "robot1");
}

std::string team_session() {
  return gate::launch_session_id(test::kHashA, {{"robot3", nonce_of("robot3")},
                                                {"robot1", nonce_of("robot1")},
                                                {"robot2", nonce_of("robot2")}});
}
}  // namespace

TEST_CASE("the session id: BLAKE2b-256 over the domain, the hash and the sorted robot:nonce lines (golden vector)") {
  // Computed independently with Python's hashlib.blake2b(digest_size=32) over
  // b'p3at-launch-session-v1\0' + b'ab'*32 + b'\n' + b'robot1:' + b'11'*16 + b'\n' + b'robot2:' + b'22'*16 + b'\n'.
  const std::string expected = "2d26562725400ea935dbb631bc4296530a3e99f108ab2bf9c7a4fcc786770dff";
  std::string hash;
  for (int i = 0; i < 32; ++i) hash += "ab";
  CHECK(gate::launch_session_id(hash, {{"robot2", std::string(32, '2')}, {"robot1", std::string(32, '1')}}) ==
        expected);
  CHECK(gate::launch_session_id(hash, {{"robot1", std::string(32, '1')}, {"robot2", std::string(32, '2')}}) ==
        expected);
  CHECK(gate::launch_session_id(hash, {{"robot1", std::string(32, '1')}, {"robot2", std::string(32, '3')}}) !=
        expected);
  const std::string a = gate::fresh_gate_nonce();
  const std::string b = gate::fresh_gate_nonce();
  CHECK(hal::is_lower_hex(a, 32));
  CHECK(a != b);
}

TEST_CASE("every teammate GO and hearing this gate: commit (session published), launch on their commitments") {
  auto a = make();
  CHECK(a.update(1'000'000, {}).state == AgreementState::waiting);
  CHECK(a.current().silent == std::vector<std::string>{"robot2", "robot3"});
  CHECK_FALSE(a.current().committed);
  CHECK(a.published().session.empty());
  CHECK(a.update(1'100'000, {current_go("robot3")}).state == AgreementState::waiting);
  CHECK(a.current().silent == std::vector<std::string>{"robot2"});
  // It echoes the nonces it has heard, so the teammates can commit too.
  CHECK(a.published().heard == std::vector<hal::HeardNonce>{{"robot3", nonce_of("robot3")}});

  const auto& c = a.update(1'200'000, {current_go("robot2", GateDecision::override_go), current_go("robot3")});
  CHECK(c.state == AgreementState::waiting);  // committed, not launched: nobody has heard it commit
  CHECK(c.committed);
  CHECK(c.session == team_session());
  CHECK(a.published().session == team_session());
  CHECK(a.published().decision == GateDecision::go);

  // One teammate committed: still waiting for the other.
  CHECK(a.update(1'300'000, {committed(current_go("robot2", GateDecision::override_go), team_session()),
                             current_go("robot3")})
            .state == AgreementState::waiting);
  const auto& done = a.update(1'400'000, {committed(current_go("robot2", GateDecision::override_go), team_session()),
                                          committed(current_go("robot3"), team_session())});
  CHECK(done.state == AgreementState::launch);
  CHECK(done.reason.find("robot1:GO,robot2:OVERRIDE,robot3:GO") != std::string::npos);
  CHECK(done.team.size() == 3);
}

TEST_CASE("verdicts that do not echo this gate's nonce count for nothing: a replay of another run, even committed") {
  auto a = make();
  // A recording of an earlier run: robot2 and robot3 said GO and committed,
  // having heard robot1's *earlier* gate (another nonce).
  const std::string old_session = gate::launch_session_id(test::kHashA, {{"robot1", nonce_of("robot1", 5)}});
  const std::vector<hal::GateVerdict> replayed{committed(hearing(test::verdict("robot2", GateDecision::go), "robot1", 5), old_session),
                                               committed(hearing(test::verdict("robot3", GateDecision::no_go), "robot1", 5), old_session)};
  CHECK(a.update(1'000'000, replayed).state == AgreementState::waiting);  // not even the NO-GO counts
  CHECK_FALSE(a.current().committed);
  const auto& d = a.update(1'000'000 + kTimeout, replayed);
  CHECK(d.state == AgreementState::silent);
  CHECK(d.reason.find("no verdict from robot2,robot3 within 5.0 s (heard robot2,robot3, but not hearing this robot)") !=
        std::string::npos);
}

TEST_CASE("own NO-GO refuses at once, even with every teammate GO; it publishes its NO-GO") {
  auto a = make(GateDecision::no_go);
  const auto& d = a.update(1'000'000, {current_go("robot2"), current_go("robot3")});
  CHECK(d.state == AgreementState::no_go);
  CHECK(d.reason.find("this robot's verdict is NO-GO") != std::string::npos);
  CHECK(d.reason.find("threshold 0.8000") != std::string::npos);
  CHECK(a.published().decision == GateDecision::no_go);
  CHECK(a.published().session.empty());
}

TEST_CASE("a teammate's NO-GO refuses; an own OVERRIDE does not overrule it; the refusal is what is published") {
  auto a = make(GateDecision::override_go);
  const auto& d = a.update(1'000'000, {hearing(test::verdict("robot2", GateDecision::no_go, test::kHashA, 0.31), "robot1")});
  CHECK(d.state == AgreementState::no_go);
  CHECK(d.reason.find("teammate robot2 says NO-GO") != std::string::npos);
  CHECK(d.reason.find("0.3100") != std::string::npos);
  CHECK(a.published().decision == GateDecision::no_go);
  CHECK(a.published().detail.find("refused: teammate robot2 says NO-GO") == 0);
}

TEST_CASE("a teammate with another mission hash: mismatch, before its decision is even looked at") {
  auto a = make();
  const auto& d = a.update(1'000'000, {hearing(test::verdict("robot2", GateDecision::no_go, test::kHashB), "robot1"),
                                       current_go("robot3")});
  CHECK(d.state == AgreementState::mismatch);
  CHECK(d.reason.find("robot2") != std::string::npos);
  CHECK(d.reason.find(test::kHashB.substr(0, 16)) != std::string::npos);
}

TEST_CASE("uncommitted, silence past the timeout refuses: not one microsecond before; never GO afterwards") {
  auto a = make();
  const std::vector<hal::GateVerdict> only3{current_go("robot3")};
  CHECK(a.update(1'000'000 + kTimeout - 1, only3).state == AgreementState::waiting);
  CHECK(a.published().decision == GateDecision::go);
  const auto& d = a.update(1'000'000 + kTimeout, only3);
  CHECK(d.state == AgreementState::silent);
  CHECK(d.silent == std::vector<std::string>{"robot2"});
  CHECK(d.reason.find("no verdict from robot2 within 5.0 s") != std::string::npos);
  CHECK(a.published().decision == GateDecision::no_go);
  CHECK(a.published().detail.find("refused: no verdict from robot2") == 0);
  // The teammate shows up late: the refusal sticks and stays what is published.
  CHECK(a.update(1'000'000 + kTimeout + 1, {current_go("robot2"), current_go("robot3")}).state ==
        AgreementState::silent);
  CHECK(a.published().decision == GateDecision::no_go);
  CHECK(a.published().heard.size() == 2);  // but it echoes them, so they hear its refusal
}

TEST_CASE("committed, a robot never refuses by timeout: in doubt only after timeout + doubt, and does not move") {
  auto a = make();
  const std::vector<hal::GateVerdict> team{current_go("robot2"), current_go("robot3")};
  CHECK(a.update(1'000'000, team).committed);
  CHECK(a.update(1'000'000 + kTimeout, team).state == AgreementState::waiting);
  CHECK(a.update(1'000'000 + kTimeout + kDoubt - 1, team).state == AgreementState::waiting);
  const auto& d = a.update(1'000'000 + kTimeout + kDoubt, team);
  CHECK(d.state == AgreementState::in_doubt);
  CHECK(d.reason.find("did not hear the commitment of robot2,robot3") != std::string::npos);
  CHECK(a.published().decision == GateDecision::go);  // not a refusal: a teammate may be moving
}

TEST_CASE("committed, a restarted teammate (another nonce) is a stranger: no launch with it, no refusal from it") {
  auto a = make();
  CHECK(a.update(1'000'000, {current_go("robot2"), current_go("robot3")}).committed);
  // robot2 restarted: new nonce, it heard us again and says NO-GO; robot3 committed.
  hal::GateVerdict reborn = hearing(test::verdict("robot2", GateDecision::no_go), "robot1");
  reborn.nonce = nonce_of("robot2", 3);
  const auto& d = a.update(1'100'000, {reborn, committed(current_go("robot3"), team_session())});
  CHECK(d.state == AgreementState::waiting);
  CHECK(a.update(1'000'000 + kTimeout + kDoubt, {reborn, committed(current_go("robot3"), team_session())}).state ==
        AgreementState::in_doubt);
}

TEST_CASE("a team of one launches on its own GO") {
  gate::TeamAgreement solo(test::verdict("robot1", GateDecision::go), {"robot1"}, 0, kTimeout);
  CHECK(solo.update(0, {}).state == AgreementState::launch);
}

// ---- the property, over randomised whole-team runs

namespace {

/// One robot of a simulated team: its agreement, when it starts and whether it
/// is alive (a silent robot never starts).
struct SimRobot {
  std::string name;
  GateDecision own = GateDecision::go;
  std::int64_t start_us = 0;
  std::int64_t timeout_us = 0;
  std::optional<gate::TeamAgreement> agreement;
  std::vector<hal::GateVerdict> inbox;  ///< latest verdict of each teammate heard
  bool stopped = false;                 ///< exited (refused, in doubt) or never runs
};

struct InFlight {
  std::int64_t at_us;
  std::size_t to;
  hal::GateVerdict verdict;
};

}  // namespace

TEST_CASE("property: in 5,000 random team runs with loss, delay, late, silent and NO-GO robots, a refusal means no launch") {
  std::mt19937_64 rng(20261124);
  int launched_runs = 0, refused_runs = 0, doubt_runs = 0;
  for (int run = 0; run < 5'000; ++run) {
    const std::size_t n = 2 + rng() % 3;
    std::vector<std::string> roster;
    for (std::size_t i = 0; i < n; ++i) roster.push_back("robot" + std::to_string(i + 1));
    const double loss = (rng() % 4 == 0) ? 0.0 : static_cast<double>(rng() % 60) / 100.0;
    std::vector<SimRobot> robots(n);
    for (std::size_t i = 0; i < n; ++i) {
      SimRobot& r = robots[i];
      r.name = roster[i];
      r.own = (rng() % 12 == 0) ? GateDecision::no_go : GateDecision::go;
      r.start_us = static_cast<std::int64_t>(rng() % 8'000'000);
      r.timeout_us = 1'000'000 + static_cast<std::int64_t>(rng() % 4'000'000);
      r.stopped = rng() % 15 == 0;  // silent: never runs
      hal::GateVerdict own = test::verdict(r.name, r.own);
      char hex[33];
      std::snprintf(hex, sizeof hex, "%016llx%016llx", static_cast<unsigned long long>(rng()),
                    static_cast<unsigned long long>(rng()));
      own.nonce = std::string(hex, 32);
      r.agreement.emplace(own, roster, r.start_us, r.timeout_us, 1'000'000);
    }
    std::vector<InFlight> flight;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::int64_t t = 0; t < 20'000'000; t += 50'000) {
      // Deliveries due now (latest verdict per sender replaces the held one).
      for (auto it = flight.begin(); it != flight.end();) {
        if (it->at_us <= t) {
          SimRobot& to = robots[it->to];
          auto held = std::find_if(to.inbox.begin(), to.inbox.end(),
                                   [&](const hal::GateVerdict& v) { return v.robot == it->verdict.robot; });
          if (held == to.inbox.end()) {
            to.inbox.push_back(it->verdict);
          } else {
            *held = it->verdict;  // (reordering: a stale one may replace a newer one; the protocol must bear it)
          }
          it = flight.erase(it);
        } else {
          ++it;
        }
      }
      for (std::size_t i = 0; i < n; ++i) {
        SimRobot& r = robots[i];
        if (r.stopped || t < r.start_us) continue;
        const auto& a = r.agreement->update(t, r.inbox);
        const bool launched = a.state == AgreementState::launch;
        // Publish every step (a launched robot keeps publishing during its mission).
        for (std::size_t j = 0; j < n; ++j) {
          if (j == i || u(rng) < loss) continue;
          flight.push_back({t + static_cast<std::int64_t>(rng() % 400'000), j, r.agreement->published()});
        }
        if (!launched && a.state != AgreementState::waiting) r.stopped = true;  // refused or in doubt: exits
      }
      // Done once every robot that runs has decided (the launched keep publishing,
      // but nobody is left to hear them).
      if (std::all_of(robots.begin(), robots.end(), [&](const SimRobot& r) {
            return r.stopped || (t >= r.start_us && r.agreement->decided());
          })) {
        break;
      }
    }
    bool any_refused = false, any_launched = false, any_doubt = false;
    for (const SimRobot& r : robots) {
      if (!r.agreement) continue;
      const auto s = r.agreement->current().state;
      any_refused |= s == AgreementState::no_go || s == AgreementState::mismatch || s == AgreementState::silent;
      any_launched |= s == AgreementState::launch;
      any_doubt |= s == AgreementState::in_doubt;
    }
    INFO("run " << run << " n=" << n << " loss=" << loss);
    CHECK_FALSE((any_refused && any_launched));
    launched_runs += any_launched;
    refused_runs += any_refused;
    doubt_runs += any_doubt;
  }
  MESSAGE("runs launched=" << launched_runs << " refused=" << refused_runs << " in_doubt=" << doubt_runs);
  // The sweep covers all three outcomes, or it proves nothing.
  CHECK(launched_runs > 500);
  CHECK(refused_runs > 500);
}
