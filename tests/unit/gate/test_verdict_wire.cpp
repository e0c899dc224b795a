// The gate verdict on the team link: its wire codec (authenticated like every
// team message, strict decoding), the protocol's acceptance rules (a forged GO
// is rejected and counted, a replay is not taken for news), teammates'
// telemetry kept for re-verification, and the backends that carry it: the
// simulated radio and real LCM udpm on the loopback.
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "fake_team_link.hpp"
#include "gate_test_util.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/lcm_team_link.hpp"
#include "p3at/hal/team_protocol.hpp"
#include "p3at/hal/team_wire.hpp"
#include "p3at/sim/radio.hpp"
#include "p3at_lcm/gate_verdict_t.hpp"

using namespace p3at;
using hal::GateDecision;
using hal::TeamChannel;
using hal::TeamDatagram;

namespace {

hal::VerdictWire wire(const std::string& robot, GateDecision decision, std::uint64_t seq = 7) {
  hal::VerdictWire w;
  w.utime_us = 123;
  w.mission_id = "relay";
  w.seq = seq;
  w.verdict = test::verdict(robot, decision);
  w.verdict.detail = "P(joint) = 0.42 < 0.8";
  return w;
}

hal::TeamLinkConfig config(const std::string& self, const std::string& mission = "relay") {
  hal::TeamLinkConfig c;
  c.mission_id = mission;
  c.self = self;
  c.roster = {"robot1", "robot2"};
  return c;
}

hal::TeamProtocol protocol(const std::string& self, std::uint8_t key_seed = 1, const std::string& mission = "relay") {
  auto p = hal::TeamProtocol::create(config(self, mission), test::gate_key(key_seed));
  REQUIRE(p.ok());
  return std::move(p.value());
}

void receive(hal::TeamProtocol& p, const TeamDatagram& d) {
  std::vector<hal::TeamNotification> delivered;
  std::vector<TeamDatagram> out;
  p.receive(0, d.channel, d.bytes, delivered, out);
  CHECK(delivered.empty());
  CHECK(out.empty());  // verdicts are never acknowledged
}

}  // namespace

TEST_CASE("decisions have one wire spelling each, and only those decode") {
  CHECK(std::string(hal::to_string(GateDecision::go)) == "GO");
  CHECK(std::string(hal::to_string(GateDecision::no_go)) == "NO-GO");
  CHECK(std::string(hal::to_string(GateDecision::override_go)) == "OVERRIDE");
  for (const auto d : {GateDecision::go, GateDecision::no_go, GateDecision::override_go}) {
    CHECK(hal::gate_decision_from_string(hal::to_string(d)) == d);
  }
  CHECK_FALSE(hal::gate_decision_from_string("go").has_value());
  CHECK_FALSE(hal::gate_decision_from_string("").has_value());
  CHECK(hal::allows_launch(GateDecision::go));
  CHECK(hal::allows_launch(GateDecision::override_go));
  CHECK_FALSE(hal::allows_launch(GateDecision::no_go));
  CHECK(hal::channel_name(TeamChannel::gate) == "P3AT_GATE");
  CHECK(hal::channel_from_name("P3AT_GATE") == TeamChannel::gate);
}

TEST_CASE("a verdict round-trips through the wire with its tag, and only the team key verifies it") {
  const auto key = test::gate_key(1);
  auto w = wire("robot2", GateDecision::override_go);
  w.verdict.heard = {{"robot1", test::nonce_of("robot1")}};
  w.verdict.session = std::string(64, 'c');
  auto bytes = hal::encode_verdict(w, key);
  REQUIRE(bytes.ok());
  auto back = hal::decode_verdict(bytes.value(), key);
  REQUIRE(back.ok());
  CHECK(back->tag_ok);
  CHECK(back->wire.seq == 7);
  CHECK(back->wire.mission_id == "relay");
  CHECK(back->wire.verdict.robot == "robot2");
  CHECK(back->wire.verdict.decision == GateDecision::override_go);
  CHECK(back->wire.verdict.mission_hash == test::kHashA);
  CHECK(back->wire.verdict.p_joint == doctest::Approx(0.9));
  CHECK(back->wire.verdict.threshold == doctest::Approx(0.8));
  CHECK(back->wire.verdict.tmax_s == doctest::Approx(60.0));
  CHECK(back->wire.verdict.detail == "P(joint) = 0.42 < 0.8");
  CHECK(back->wire.verdict.nonce == test::nonce_of("robot2"));
  CHECK(back->wire.verdict.session == std::string(64, 'c'));
  CHECK(back->wire.verdict.heard == w.verdict.heard);

  auto other = hal::decode_verdict(bytes.value(), test::gate_key(9));
  REQUIRE(other.ok());
  CHECK_FALSE(other->tag_ok);
  // Any flipped byte of the tagged part breaks the tag (or the layout).
  auto flipped = bytes.value();
  flipped[flipped.size() - 40] ^= 0x01;
  auto f = hal::decode_verdict(flipped, key);
  CHECK((!f.ok() || !f->tag_ok));
}

TEST_CASE("the encoder refuses what the decoder would call malformed") {
  const auto key = test::gate_key(1);
  auto w = wire("robot1", GateDecision::go);
  w.verdict.mission_hash = "ABC";
  CHECK_FALSE(hal::encode_verdict(w, key).ok());
  w.verdict.mission_hash = std::string(64, 'A');  // upper case is not the canonical spelling
  CHECK_FALSE(hal::encode_verdict(w, key).ok());
  w = wire("robot1", GateDecision::go);
  w.verdict.p_joint = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(hal::encode_verdict(w, key).ok());
  w = wire("robot1", GateDecision::go);
  w.verdict.detail = std::string(300, 'x');
  CHECK_FALSE(hal::encode_verdict(w, key).ok());
}

TEST_CASE("decoding is strict: unknown decision, bad hash, non-finite numbers, truncation") {
  const auto key = test::gate_key(1);
  auto raw_bytes = [](p3at_lcm::gate_verdict_t msg) {
    std::vector<std::uint8_t> out(static_cast<std::size_t>(msg.getEncodedSize()));
    (void)msg.encode(out.data(), 0, static_cast<int>(out.size()));
    return out;
  };
  p3at_lcm::gate_verdict_t good;  // lcm-gen leaves numbers uninitialised: set every field
  good.utime = 0;
  good.p_time = good.p_radius = good.p_joint = 0.5;
  good.threshold = 0.8;
  good.tmax_s = 60.0;
  good.rmax_m = 0.5;
  good.mission_id = "relay";
  good.robot = "robot1";
  good.seq = 1;
  good.mission_hash = test::kHashA;
  good.decision = "GO";
  good.nonce = test::nonce_of("robot1");
  good.num_heard = 1;
  good.heard_robot = {"robot2"};
  good.heard_nonce = {test::nonce_of("robot2")};
  good.tag_len = 0;
  REQUIRE(hal::decode_verdict(raw_bytes(good), key).ok());  // untagged: decodes, tag fails
  CHECK_FALSE(hal::decode_verdict(raw_bytes(good), key)->tag_ok);

  auto bad = good;
  bad.decision = "MAYBE";
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.mission_hash = std::string(64, 'g');
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.p_radius = std::numeric_limits<double>::infinity();
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.seq = -1;
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  // The launch session's fields: a nonce is exactly 32 lowercase hex digits,
  // a session empty or 64, every heard nonce 32.
  bad = good;
  bad.nonce = "";
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.nonce = std::string(32, 'A');
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.session = std::string(63, 'a');
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.session = std::string(64, 'a');
  CHECK(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.heard_nonce = {"xyz"};
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  bad = good;
  bad.num_heard = 33;
  bad.heard_robot.assign(33, "robot2");
  bad.heard_nonce.assign(33, test::nonce_of("robot2"));
  CHECK_FALSE(hal::decode_verdict(raw_bytes(bad), key).ok());
  auto bytes = raw_bytes(good);
  for (std::size_t cut = 0; cut < bytes.size(); cut += 7) {
    CHECK_FALSE(hal::decode_verdict(std::span(bytes.data(), cut), key).ok());
  }
  bytes.push_back(0);
  CHECK_FALSE(hal::decode_verdict(bytes, key).ok());
  // A status message on the gate channel is not a verdict.
  hal::StatusWire status;
  status.mission_id = "relay";
  status.status.robot = "robot1";
  CHECK_FALSE(hal::decode_verdict(hal::encode_status(status, key).value(), key).ok());
}

TEST_CASE("the protocol keeps each teammate's newest authenticated verdict and counts every rejection") {
  auto robot1 = protocol("robot1");
  auto robot2 = protocol("robot2");
  auto forger = protocol("robot2", 42);  // right name, wrong key

  auto go = robot2.verdict(test::verdict("ignored", GateDecision::go));
  REQUIRE(go.ok());
  CHECK(go->channel == TeamChannel::gate);
  receive(robot1, go.value());
  REQUIRE(robot1.teammate_verdicts().size() == 1);
  CHECK(robot1.teammate_verdicts()[0].robot == "robot2");  // the link sets the sender
  CHECK(robot1.teammate_verdicts()[0].decision == GateDecision::go);
  CHECK(robot1.stats().verdicts_accepted == 1);

  // A forged NO-GO (wrong key) neither replaces the GO nor goes unnoticed.
  auto forged = forger.verdict(test::verdict("robot2", GateDecision::no_go));
  REQUIRE(forged.ok());
  receive(robot1, forged.value());
  CHECK(robot1.stats().rejected_bad_tag == 1);
  CHECK(robot1.teammate_verdicts()[0].decision == GateDecision::go);

  // A newer genuine verdict replaces it; replaying the old one changes nothing.
  auto no_go = robot2.verdict(test::verdict("robot2", GateDecision::no_go, test::kHashA, 0.3));
  receive(robot1, no_go.value());
  CHECK(robot1.teammate_verdicts()[0].decision == GateDecision::no_go);
  receive(robot1, go.value());
  CHECK(robot1.stats().rejected_replay == 1);
  CHECK(robot1.teammate_verdicts()[0].decision == GateDecision::no_go);
  CHECK(robot1.stats().verdicts_accepted == 2);

  // Own verdict looped back: ignored, not counted.
  receive(robot1, robot1.verdict(test::verdict("robot1", GateDecision::go)).value());
  CHECK(robot1.teammate_verdicts().size() == 1);

  // Another mission's team, and a stranger with the right key.
  auto other_team = protocol("robot2", 1, "other-mission");
  receive(robot1, other_team.verdict(test::verdict("robot2", GateDecision::go)).value());
  CHECK(robot1.stats().rejected_other_mission == 1);
  auto stranger_cfg = config("robot9");
  stranger_cfg.roster = {"robot9", "robot1"};
  auto stranger = hal::TeamProtocol::create(stranger_cfg, test::gate_key(1));
  REQUIRE(stranger.ok());
  receive(robot1, stranger->verdict(test::verdict("robot9", GateDecision::go)).value());
  CHECK(robot1.stats().rejected_unknown_sender == 1);
  CHECK(robot1.stats().verdicts_accepted == 2);

  // Garbage on the channel.
  receive(robot1, TeamDatagram{TeamChannel::gate, {1, 2, 3}});
  CHECK(robot1.stats().malformed == 1);
}

TEST_CASE("teammates' telemetry is kept (newest only) for in-mission re-verification") {
  auto robot1 = protocol("robot1");
  auto robot2 = protocol("robot2");
  hal::Telemetry t;
  t.state = "drive";
  t.x_m = 2.5;
  t.cycles = 10;
  auto first = robot2.telemetry(t);
  t.x_m = 2.7;
  t.cycles = 11;
  auto second = robot2.telemetry(t);
  receive(robot1, second.value());
  receive(robot1, first.value());  // arrives late: stale
  REQUIRE(robot1.teammate_telemetry().size() == 1);
  CHECK(robot1.teammate_telemetry()[0].robot == "robot2");
  CHECK(robot1.teammate_telemetry()[0].x_m == doctest::Approx(2.7));
  CHECK(robot1.stats().telemetry_accepted == 1);
  CHECK(robot1.stats().rejected_replay == 1);
  auto forged = protocol("robot2", 42).telemetry(t);
  receive(robot1, forged.value());
  CHECK(robot1.stats().rejected_bad_tag == 1);
}

TEST_CASE("SimTeamLink carries verdicts between simulated robots") {
  auto radio = sim::SimRadio::create({}, 3);
  REQUIRE(radio.ok());
  auto a = sim::SimTeamLink::create(**radio, config("robot1"), test::gate_key(1));
  auto b = sim::SimTeamLink::create(**radio, config("robot2"), test::gate_key(1));
  REQUIRE((a.ok() && b.ok()));
  std::vector<hal::TeamNotification> got;
  REQUIRE((*a)->poll(0, got).ok());
  REQUIRE((*a)->publish_verdict(test::verdict("robot1", GateDecision::go)).ok());
  REQUIRE((*b)->poll(1'000'000, got).ok());
  REQUIRE((*b)->teammate_verdicts().size() == 1);
  CHECK((*b)->teammate_verdicts()[0].robot == "robot1");
  CHECK((*b)->teammate_verdicts()[0].mission_hash == test::kHashA);
  CHECK((*b)->stats().verdicts_accepted == 1);
}

TEST_CASE("LcmTeamLink carries verdicts and telemetry over real udpm on the loopback; a forged GO is counted") {
  const std::string url = "udpm://239.255.76.67:" + std::to_string(31000 + ::getpid() % 20000) + "?ttl=0";
  auto open = [&](const std::string& self, std::uint8_t key_seed) {
    auto link = hal::open_lcm_team_link(url, config(self), test::gate_key(key_seed));
    REQUIRE_MESSAGE(link.ok(), (link.ok() ? "" : link.error().message));
    return std::move(link.value());
  };
  auto robot1 = open("robot1", 1);
  auto robot2 = open("robot2", 1);
  auto forger = open("robot2", 42);
  hal::SteadyClock clock;
  std::vector<hal::TeamNotification> got;
  const auto deadline = clock.now_us() + 10'000'000;
  bool done = false;
  while (!done && clock.now_us() < deadline) {
    REQUIRE(forger->publish_verdict(test::verdict("robot2", GateDecision::go, test::kHashB)).ok());
    REQUIRE(robot2->publish_verdict(test::verdict("robot2", GateDecision::go)).ok());
    hal::Telemetry t;
    t.state = "wait";
    t.cycles = 1;
    REQUIRE(robot2->publish_telemetry(t).ok());
    REQUIRE(robot1->poll(clock.now_us(), got).ok());
    REQUIRE(robot2->poll(clock.now_us(), got).ok());
    REQUIRE(forger->poll(clock.now_us(), got).ok());
    done = !robot1->teammate_verdicts().empty() && !robot1->teammate_telemetry().empty() &&
           robot1->stats().rejected_bad_tag > 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  REQUIRE(done);
  CHECK(robot1->teammate_verdicts()[0].mission_hash == test::kHashA);  // never the forger's
  CHECK(robot1->teammate_telemetry()[0].state == "wait");
}

TEST_CASE("FakeTeamLink: connected links see each other's verdicts and telemetry") {
  test::FakeTeamLink a("robot1");
  test::FakeTeamLink b("robot2");
  test::FakeTeamLink::connect(a, b);
  REQUIRE(a.publish_verdict(test::verdict("whoever", GateDecision::go)).ok());
  REQUIRE(b.teammate_verdicts().size() == 1);
  CHECK(b.teammate_verdicts()[0].robot == "robot1");
  CHECK(a.verdicts_sent.size() == 1);
  hal::Telemetry t;
  t.x_m = 4.0;
  REQUIRE(a.publish_telemetry(t).ok());
  REQUIRE(b.teammate_telemetry().size() == 1);
  CHECK(b.teammate_telemetry()[0].robot == "robot1");
  a.fail_publish_verdict = true;
  CHECK_FALSE(a.publish_verdict(test::verdict("robot1", GateDecision::go)).ok());
}
