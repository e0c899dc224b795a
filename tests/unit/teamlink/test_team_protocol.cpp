// The transport-independent protocol: authentication, every rejection kind,
// replay, acknowledgement and retransmission, status. Datagrams are carried by
// hand, so each test decides exactly what is delivered, lost or replayed.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "p3at/hal/team_protocol.hpp"
#include "p3at/hal/team_wire.hpp"
#include "p3at_lcm/notification_t.hpp"
#include "team_test_util.hpp"

using namespace p3at;
using hal::TeamChannel;
using hal::TeamDatagram;
using hal::TeamNotification;
using hal::TeamProtocol;

namespace {

TeamProtocol make(const std::string& self, std::uint8_t key_seed = 1, std::uint64_t first_seq = 1000,
                  const std::string& mission = "cbrn-search-1",
                  std::vector<std::string> roster = {"alpha", "bravo", "charlie"}) {
  auto config = test::team_config(self, std::move(roster), mission);
  config.first_seq = first_seq;
  auto p = TeamProtocol::create(config, test::fixed_key(key_seed));
  REQUIRE(p.ok());
  return std::move(p.value());
}

// One robot's inbox: what receive() delivered and sent back.
struct Rx {
  std::vector<TeamNotification> delivered;
  std::vector<TeamDatagram> out;
};

Rx deliver(TeamProtocol& to, const std::vector<TeamDatagram>& datagrams, std::int64_t now_us = 0) {
  Rx rx;
  for (const auto& d : datagrams) to.receive(now_us, d.channel, d.bytes, rx.delivered, rx.out);
  return rx;
}

std::uint64_t rejections(const hal::TeamLinkStats& s) {
  return s.rejected_unknown_sender + s.rejected_bad_tag + s.rejected_replay + s.rejected_other_mission + s.malformed;
}

}  // namespace

TEST_CASE("a notification is delivered once, acknowledged, and then acknowledged() is true") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  std::vector<TeamDatagram> out;
  auto seq = alpha.notify("at_door", {"bravo"}, out);
  REQUIRE(seq.ok());
  CHECK(seq.value() == 1000);
  REQUIRE(out.size() == 1);
  CHECK(out[0].channel == TeamChannel::notify);
  CHECK_FALSE(alpha.acknowledged(seq.value()));

  auto rx = deliver(bravo, out);
  REQUIRE(rx.delivered.size() == 1);
  CHECK(rx.delivered[0].sender == "alpha");
  CHECK(rx.delivered[0].message == "at_door");
  CHECK(rx.delivered[0].seq == 1000);
  CHECK(bravo.stats().accepted == 1);
  REQUIRE(rx.out.size() == 1);  // the ack

  auto ack = hal::decode_notification(rx.out[0].bytes, test::fixed_key(1));
  REQUIRE(ack.ok());
  CHECK(ack->tag_ok);
  CHECK(ack->wire.is_ack);
  CHECK(ack->wire.sender == "bravo");
  CHECK(ack->wire.ack_sender == "alpha");
  CHECK(ack->wire.ack_seq == 1000);

  auto back = deliver(alpha, rx.out);
  CHECK(back.delivered.empty());  // an ack is not a notification
  CHECK(alpha.stats().acks_received == 1);
  CHECK(alpha.acknowledged(seq.value()));
  CHECK(alpha.unacknowledged() == 0);
  CHECK(alpha.stats().sent == 1);
  CHECK(rejections(alpha.stats()) == 0);
  CHECK(rejections(bravo.stats()) == 0);
}

TEST_CASE("retransmitted every interval until acknowledged; duplicates are re-acked, never re-delivered") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  std::vector<TeamDatagram> out;
  alpha.tick(0, out);
  REQUIRE(out.empty());
  auto seq = alpha.notify("go", {"bravo"}, out).value();
  out.clear();  // first transmission lost

  alpha.tick(199'999, out);
  CHECK(out.empty());
  alpha.tick(200'000, out);
  REQUIRE(out.size() == 1);
  CHECK(alpha.stats().retransmissions == 1);

  auto rx = deliver(bravo, out);  // arrives; its ack is lost
  CHECK(rx.delivered.size() == 1);
  out.clear();

  alpha.tick(399'999, out);
  CHECK(out.empty());
  alpha.tick(400'000, out);
  REQUIRE(out.size() == 1);
  CHECK(alpha.stats().retransmissions == 2);
  auto rx2 = deliver(bravo, out);
  CHECK(rx2.delivered.empty());                 // at most once
  CHECK(bravo.stats().accepted == 1);
  CHECK(bravo.stats().rejected_replay == 1);    // a legitimate duplicate is counted as a replay
  REQUIRE(rx2.out.size() == 1);                 // but acknowledged again
  deliver(alpha, rx2.out);
  CHECK(alpha.acknowledged(seq));
  out.clear();
  alpha.tick(10'000'000, out);
  CHECK(out.empty());  // no more retransmissions
  CHECK(alpha.stats().retransmissions == 2);
}

TEST_CASE("with several recipients, retransmissions go to those that have not acknowledged") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  auto charlie = make("charlie");
  std::vector<TeamDatagram> out;
  alpha.tick(0, out);
  auto seq = alpha.notify("found", {"bravo", "charlie"}, out).value();
  deliver(alpha, deliver(bravo, out).out);  // only bravo hears it and acks
  CHECK_FALSE(alpha.acknowledged(seq));
  out.clear();
  alpha.tick(200'000, out);
  REQUIRE(out.size() == 1);
  auto again = hal::decode_notification(out[0].bytes, test::fixed_key(1));
  REQUIRE(again.ok());
  CHECK(again->wire.recipients == std::vector<std::string>{"charlie"});
  CHECK(again->wire.seq == seq);
  auto bravo_rx = deliver(bravo, out);  // not addressed to bravo any more: ignored silently
  CHECK(bravo_rx.out.empty());
  CHECK(bravo.stats().rejected_replay == 0);
  auto charlie_rx = deliver(charlie, out);
  CHECK(charlie_rx.delivered.size() == 1);
  deliver(alpha, charlie_rx.out);
  CHECK(alpha.acknowledged(seq));
}

TEST_CASE("every rejection kind is counted and never delivered or acknowledged") {
  auto bravo = make("bravo");
  std::vector<TeamDatagram> out;

  SUBCASE("unknown sender (holds the key, but not in bravo's roster)") {
    auto mallory = make("mallory", 1, 1000, "cbrn-search-1", {"mallory", "bravo"});
    REQUIRE(mallory.notify("abort", {"bravo"}, out).ok());
    auto rx = deliver(bravo, out);
    CHECK(rx.delivered.empty());
    CHECK(rx.out.empty());
    CHECK(bravo.stats().rejected_unknown_sender == 1);
  }
  SUBCASE("bad tag (a team member's name, the wrong key)") {
    auto forger = make("alpha", 99);
    REQUIRE(forger.notify("abort", {"bravo"}, out).ok());
    auto rx = deliver(bravo, out);
    CHECK(rx.delivered.empty());
    CHECK(rx.out.empty());
    CHECK(bravo.stats().rejected_bad_tag == 1);
  }
  SUBCASE("missing tag") {
    p3at_lcm::notification_t m;
    m.utime = 0;
    m.mission_id = "cbrn-search-1";
    m.sender = "alpha";
    m.seq = 5;
    m.message = "abort";
    m.is_ack = 0;
    m.ack_seq = 0;
    m.num_recipients = 1;
    m.recipients = {"bravo"};
    m.tag_len = 0;
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
    REQUIRE(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())) > 0);
    auto rx = deliver(bravo, {{TeamChannel::notify, bytes}});
    CHECK(rx.delivered.empty());
    CHECK(bravo.stats().rejected_bad_tag == 1);
  }
  SUBCASE("other mission (right key, right name)") {
    auto other = make("alpha", 1, 1000, "another-mission");
    REQUIRE(other.notify("abort", {"bravo"}, out).ok());
    auto rx = deliver(bravo, out);
    CHECK(rx.delivered.empty());
    CHECK(bravo.stats().rejected_other_mission == 1);
  }
  SUBCASE("malformed") {
    auto rx = deliver(bravo, {{TeamChannel::notify, {1, 2, 3}}, {TeamChannel::status, {}}});
    CHECK(rx.delivered.empty());
    CHECK(bravo.stats().malformed == 2);
  }
  SUBCASE("replay of a captured notification, even after newer ones") {
    auto alpha = make("alpha");
    REQUIRE(alpha.notify("at_door", {"bravo"}, out).ok());
    const auto captured = out;
    CHECK(deliver(bravo, out).delivered.size() == 1);
    out.clear();
    REQUIRE(alpha.notify("inside", {"bravo"}, out).ok());
    CHECK(deliver(bravo, out).delivered.size() == 1);
    auto rx = deliver(bravo, captured);
    CHECK(rx.delivered.empty());
    CHECK(bravo.stats().rejected_replay == 1);
    CHECK(bravo.stats().accepted == 2);
  }
}

TEST_CASE("a notification seen before any other from its sender, or reordered, is delivered") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  std::vector<TeamDatagram> first;
  std::vector<TeamDatagram> second;
  REQUIRE(alpha.notify("a", {"bravo"}, first).ok());
  REQUIRE(alpha.notify("b", {"bravo"}, second).ok());
  auto rx = deliver(bravo, second);
  auto rx2 = deliver(bravo, first);  // overtaken on the radio
  REQUIRE(rx.delivered.size() == 1);
  REQUIRE(rx2.delivered.size() == 1);
  CHECK(rx.delivered[0].message == "b");
  CHECK(rx2.delivered[0].message == "a");
  CHECK(bravo.stats().rejected_replay == 0);
}

TEST_CASE("a restarted sender with a newer first_seq is accepted; an older one looks like replays") {
  auto bravo = make("bravo");
  std::vector<TeamDatagram> out;
  {
    auto alpha = make("alpha", 1, 5000);
    REQUIRE(alpha.notify("a", {"bravo"}, out).ok());
    REQUIRE(alpha.notify("b", {"bravo"}, out).ok());
    CHECK(deliver(bravo, out).delivered.size() == 2);
  }
  out.clear();
  auto restarted = make("alpha", 1, 9000);  // e.g. wall-clock microseconds at the restart
  REQUIRE(restarted.notify("a", {"bravo"}, out).ok());
  CHECK(deliver(bravo, out).delivered.size() == 1);
  out.clear();
  auto clock_stepped_back = make("alpha", 1, 5000);
  REQUIRE(clock_stepped_back.notify("a", {"bravo"}, out).ok());
  CHECK(deliver(bravo, out).delivered.empty());
  CHECK(bravo.stats().rejected_replay == 1);
}

TEST_CASE("own looped-back messages, messages for others and telemetry are ignored without counting") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  auto charlie = make("charlie");
  std::vector<TeamDatagram> out;
  REQUIRE(alpha.notify("x", {"charlie"}, out).ok());
  auto tel = alpha.telemetry({});
  REQUIRE(tel.ok());
  out.push_back(tel.value());
  auto self_rx = deliver(alpha, out);
  auto bravo_rx = deliver(bravo, out);
  CHECK(self_rx.delivered.empty());
  CHECK(self_rx.out.empty());
  CHECK(bravo_rx.delivered.empty());
  CHECK(bravo_rx.out.empty());
  CHECK(rejections(alpha.stats()) == 0);
  CHECK(rejections(bravo.stats()) == 0);
  CHECK(deliver(charlie, out).delivered.size() == 1);
}

TEST_CASE("a forged or replayed acknowledgement does not complete a notification") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  auto forger = make("bravo", 42);  // right name, wrong key
  std::vector<TeamDatagram> out;
  auto seq = alpha.notify("go", {"bravo"}, out).value();
  auto forged = deliver(forger, out);  // the forger cannot verify it, so it does not even ack
  CHECK(forged.out.empty());
  CHECK(forger.stats().rejected_bad_tag == 1);

  // A forged ack built by hand with the wrong key.
  hal::NotificationWire ack;
  ack.mission_id = "cbrn-search-1";
  ack.sender = "bravo";
  ack.message = "go";
  ack.is_ack = true;
  ack.ack_sender = "alpha";
  ack.ack_seq = seq;
  deliver(alpha, {{TeamChannel::notify, hal::encode_notification(ack, test::fixed_key(42)).value()}});
  CHECK_FALSE(alpha.acknowledged(seq));
  CHECK(alpha.stats().rejected_bad_tag == 1);
  CHECK(alpha.stats().acks_received == 0);

  // A genuine ack of an older notification does not complete a newer one.
  ack.ack_seq = seq - 1;
  deliver(alpha, {{TeamChannel::notify, hal::encode_notification(ack, test::fixed_key(1)).value()}});
  CHECK(alpha.stats().acks_received == 1);
  CHECK_FALSE(alpha.acknowledged(seq));

  deliver(alpha, deliver(bravo, out).out);
  CHECK(alpha.acknowledged(seq));
}

TEST_CASE("status: authenticated, latest only, in roster order; a forged abort changes nothing") {
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  auto charlie = make("charlie");
  auto forger = make("charlie", 77);

  auto running = charlie.status({"ignored", "running", "GoToDoor", "", 0.93});
  REQUIRE(running.ok());
  deliver(alpha, {running.value()});
  REQUIRE(alpha.teammate_status().size() == 1);
  CHECK(alpha.teammate_status()[0].robot == "charlie");  // robot is always the sender's name
  CHECK(alpha.teammate_status()[0].phase == "running");
  CHECK(alpha.teammate_status()[0].p_success == doctest::Approx(0.93));

  auto forged = forger.status({"charlie", "aborted", "GoToDoor", "forged", 0.0});
  REQUIRE(forged.ok());
  deliver(alpha, {forged.value()});
  CHECK(alpha.teammate_status()[0].phase == "running");
  CHECK(alpha.stats().rejected_bad_tag == 1);

  deliver(alpha, {bravo.status({"", "gate", "", "p=0.95 >= 0.9", 0.95}).value()});
  REQUIRE(alpha.teammate_status().size() == 2);
  CHECK(alpha.teammate_status()[0].robot == "bravo");
  CHECK(alpha.teammate_status()[1].robot == "charlie");

  auto finished = charlie.status({"", "finished", "Done", "", 0.93});
  REQUIRE(finished.ok());
  deliver(alpha, {finished.value()});
  CHECK(alpha.teammate_status()[1].phase == "finished");
  deliver(alpha, {running.value()});  // replayed / stale
  CHECK(alpha.teammate_status()[1].phase == "finished");
  CHECK(alpha.stats().rejected_replay == 1);

  auto nan_p = bravo.status({"", "running", "", "", std::nan("")});
  REQUIRE(nan_p.ok());
  deliver(alpha, {nan_p.value()});
  CHECK(alpha.teammate_status()[0].p_success == -1.0);
}

TEST_CASE("notify() refuses bad requests with clear errors, and too many outstanding notifications") {
  auto alpha = make("alpha");
  std::vector<TeamDatagram> out;
  auto self = alpha.notify("m", {"alpha"}, out);
  REQUIRE_FALSE(self.ok());
  CHECK(self.error().message.find("itself") != std::string::npos);
  auto unknown = alpha.notify("m", {"zulu"}, out);
  REQUIRE_FALSE(unknown.ok());
  CHECK(unknown.error().message.find("'zulu' is not in the team roster") != std::string::npos);
  CHECK_FALSE(alpha.notify("m", {"bravo", "bravo"}, out).ok());
  CHECK_FALSE(alpha.notify("", {"bravo"}, out).ok());
  CHECK_FALSE(alpha.notify(std::string(200, 'm'), {"bravo"}, out).ok());
  CHECK(out.empty());
  CHECK(alpha.stats().sent == 0);

  auto broadcast = alpha.notify("hello", {}, out);
  REQUIRE(broadcast.ok());
  CHECK(alpha.acknowledged(broadcast.value()));
  CHECK_FALSE(alpha.acknowledged(broadcast.value() + 1));  // never issued
  CHECK_FALSE(alpha.acknowledged(1));

  for (std::size_t i = 0; i < 64; ++i) REQUIRE(alpha.notify("m" + std::to_string(i), {"bravo"}, out).ok());
  auto full = alpha.notify("one-too-many", {"bravo"}, out);
  REQUIRE_FALSE(full.ok());
  CHECK(full.error().code == Error::Code::state);
}

TEST_CASE("configuration errors name the problem") {
  auto bad = [](hal::TeamLinkConfig c) {
    auto s = hal::validate_team_link_config(c);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().code == Error::Code::invalid_argument);
    return s.error().message;
  };
  CHECK(hal::validate_team_link_config(test::team_config("alpha")).ok());
  CHECK(bad(test::team_config("zulu")).find("not in the roster") != std::string::npos);
  CHECK(bad(test::team_config("alpha", {"alpha", "alpha"})).find("twice") != std::string::npos);
  CHECK(bad(test::team_config("alpha", {"alpha"}, "")).find("mission id") != std::string::npos);
  auto c = test::team_config("alpha");
  c.first_seq = 0;
  CHECK(bad(c).find("first_seq") != std::string::npos);
  c = test::team_config("alpha");
  c.retransmit_interval_us = 0;
  CHECK(bad(c).find("retransmit") != std::string::npos);
  CHECK_FALSE(TeamProtocol::create(test::team_config("zulu"), test::fixed_key()).ok());
}

TEST_CASE("the launch session: messages of another session (a recording of another run) are counted, never delivered") {
  const std::string session_a(64, 'a');
  const std::string session_b(64, 'b');
  auto alpha = make("alpha");
  auto bravo = make("bravo");
  alpha.set_session(session_a);
  bravo.set_session(session_b);  // bravo belongs to another run
  std::vector<TeamDatagram> out;
  REQUIRE(alpha.notify("at_door", {"bravo"}, out).ok());
  out.push_back(alpha.status({"alpha", "running", "GoToDoor", "", 0.9}).value());
  out.push_back(alpha.telemetry(hal::Telemetry{"alpha", "GoToDoor"}).value());
  auto rx = deliver(bravo, out, 5'000);
  CHECK(rx.delivered.empty());
  CHECK(rx.out.empty());  // not even acknowledged
  CHECK(bravo.stats().rejected_other_session == 3);
  CHECK(bravo.teammate_status().empty());
  CHECK(bravo.teammate_telemetry().empty());
  CHECK_FALSE(bravo.last_heard_us("alpha").has_value());
  // The session is inside the tag: rewriting it on the wire breaks authentication.
  auto forged = hal::decode_notification(out[0].bytes, test::fixed_key(1)).value().wire;
  forged.session = session_b;
  auto reencoded = hal::encode_notification(forged, test::fixed_key(99)).value();  // a forger lacks the key
  deliver(bravo, {{TeamChannel::notify, reencoded}});
  CHECK(bravo.stats().rejected_bad_tag == 1);

  // The same session: delivered, and the sender counts as heard at that time.
  bravo.set_session(session_a);
  rx = deliver(bravo, out, 7'000);
  CHECK(rx.delivered.size() == 1);
  CHECK(bravo.last_heard_us("alpha") == 7'000);
  CHECK(bravo.teammate_status().size() == 1);
  // A session that is not 64 lowercase hex digits is ignored.
  bravo.set_session("nonsense");
  CHECK(bravo.session() == session_a);
}
