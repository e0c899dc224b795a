// The team agreement rules (docs/launch-gate.md), one by one, and that the
// first decision sticks.
#include <doctest/doctest.h>

#include "gate_test_util.hpp"
#include "p3at/launch_gate/team_agreement.hpp"

using namespace p3at;
using gate::AgreementState;
using gate::GateDecision;

namespace {
const std::vector<std::string> kTeam{"robot1", "robot2", "robot3"};
constexpr std::int64_t kTimeout = 5'000'000;

gate::TeamAgreement make(GateDecision own = GateDecision::go) {
  return gate::TeamAgreement(test::verdict("robot1", own), kTeam, 1'000'000, kTimeout);
}
}  // namespace

TEST_CASE("every teammate GO for the same hash: launch, naming every vote") {
  auto a = make();
  CHECK(a.update(1'000'000, {}).state == AgreementState::waiting);
  CHECK(a.current().silent == std::vector<std::string>{"robot2", "robot3"});
  CHECK(a.update(1'100'000, {test::verdict("robot3", GateDecision::go)}).state == AgreementState::waiting);
  CHECK(a.current().silent == std::vector<std::string>{"robot2"});
  const auto& done = a.update(1'200'000, {test::verdict("robot2", GateDecision::override_go),
                                          test::verdict("robot3", GateDecision::go)});
  CHECK(done.state == AgreementState::launch);
  CHECK(done.reason.find("robot1:GO,robot2:OVERRIDE,robot3:GO") != std::string::npos);
  CHECK(done.team.size() == 3);
  CHECK(done.silent.empty());
}

TEST_CASE("own NO-GO refuses at once, even with every teammate GO") {
  auto a = make(GateDecision::no_go);
  const auto& d = a.update(1'000'000, {test::verdict("robot2", GateDecision::go), test::verdict("robot3", GateDecision::go)});
  CHECK(d.state == AgreementState::no_go);
  CHECK(d.reason.find("this robot's verdict is NO-GO") != std::string::npos);
  CHECK(d.reason.find("threshold 0.8000") != std::string::npos);
}

TEST_CASE("a teammate's NO-GO refuses; an own OVERRIDE does not overrule it") {
  auto a = make(GateDecision::override_go);
  const auto& d = a.update(1'000'000, {test::verdict("robot2", GateDecision::no_go, test::kHashA, 0.31)});
  CHECK(d.state == AgreementState::no_go);
  CHECK(d.reason.find("teammate robot2 says NO-GO") != std::string::npos);
  CHECK(d.reason.find("0.3100") != std::string::npos);
}

TEST_CASE("a teammate with another mission hash: mismatch, before its decision is even looked at") {
  auto a = make();
  const auto& d = a.update(1'000'000, {test::verdict("robot2", GateDecision::no_go, test::kHashB),
                                       test::verdict("robot3", GateDecision::go)});
  CHECK(d.state == AgreementState::mismatch);
  CHECK(d.reason.find("robot2") != std::string::npos);
  CHECK(d.reason.find(test::kHashB.substr(0, 16)) != std::string::npos);
}

TEST_CASE("silence past the timeout refuses and names the silent; not one microsecond before") {
  auto a = make();
  const std::vector<gate::GateVerdict> only3{test::verdict("robot3", GateDecision::go)};
  CHECK(a.update(1'000'000 + kTimeout - 1, only3).state == AgreementState::waiting);
  const auto& d = a.update(1'000'000 + kTimeout, only3);
  CHECK(d.state == AgreementState::silent);
  CHECK(d.silent == std::vector<std::string>{"robot2"});
  CHECK(d.reason.find("no verdict from robot2 within 5.0 s") != std::string::npos);
}

TEST_CASE("the first decision sticks; a verdict from outside the roster counts for nothing") {
  auto a = make();
  CHECK(a.update(1'000'000, {test::verdict("robot2", GateDecision::no_go)}).state == AgreementState::no_go);
  CHECK(a.update(1'000'001, {test::verdict("robot2", GateDecision::go), test::verdict("robot3", GateDecision::go)}).state ==
        AgreementState::no_go);
  CHECK(a.decided());

  auto b = make();
  CHECK(b.update(1'000'000, {test::verdict("robot9", GateDecision::go), test::verdict("robot2", GateDecision::go)})
            .state == AgreementState::waiting);
  CHECK(b.current().silent == std::vector<std::string>{"robot3"});
}

TEST_CASE("a team of one launches on its own GO") {
  gate::TeamAgreement solo(test::verdict("robot1", GateDecision::go), {"robot1"}, 0, kTimeout);
  CHECK(solo.update(0, {}).state == AgreementState::launch);
}
