// The wire codec: LCM encodings, the HMAC tag, and every way bytes can be bad.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "p3at/hal/team_wire.hpp"
#include "p3at_lcm/notification_t.hpp"
#include "team_test_util.hpp"

using namespace p3at;
using hal::NotificationWire;

namespace {

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

NotificationWire golden_notification() {
  NotificationWire w;
  w.utime_us = 1700000000000000;
  w.mission_id = "cbrn-search-1";
  w.session = "abababababababababababababababababababababababababababababababab";
  w.sender = "alpha";
  w.seq = 42;
  w.message = "at_door";
  w.recipients = {"bravo", "charlie"};
  return w;
}

// Computed independently of this code base (Python's struct + hmac modules,
// and lcm-gen's fingerprint algorithm re-implemented in Python, checked
// against the type's earlier fingerprint 4ad14480de4b6677): the LCM encoding
// of golden_notification() with tag_len 0, tagged with HMAC-SHA-512 truncated
// to 32 bytes under the key 01 02 ... 20. The session is inside the tag.
const std::string kGoldenHex =
    "a1651b5eea7cc84a00060a24181e40000000000e6362726e2d7365617263682d310000000041616261626162616261626162"
    "6162616261626162616261626162616261626162616261626162616261626162616261626162616261626162616261626162"
    "61620000000006616c70686100000000000000002a0000000861745f646f6f72000000000001000000000000000000000200"
    "000006627261766f0000000008636861726c69650000208ef9f617da18625becaa26910c019427c5dbd1eca8e7d0e7f17c1d"
    "8189886fe9";

std::vector<std::uint8_t> encode_raw(const p3at_lcm::notification_t& msg) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(msg.getEncodedSize()));
  REQUIRE(msg.encode(out.data(), 0, static_cast<int>(out.size())) == static_cast<int>(out.size()));
  return out;
}

p3at_lcm::notification_t raw_notification() {
  p3at_lcm::notification_t m;
  m.utime = 1;
  m.mission_id = "m";
  m.sender = "alpha";
  m.seq = 5;
  m.message = "go";
  m.is_ack = 0;
  m.ack_seq = 0;
  m.num_recipients = 1;
  m.recipients = {"bravo"};
  m.tag_len = 0;
  return m;
}

}  // namespace

TEST_CASE("notification encoding matches an independently computed golden vector (format + HMAC)") {
  const auto key = test::fixed_key(1);
  auto bytes = hal::encode_notification(golden_notification(), key);
  REQUIRE(bytes.ok());
  CHECK(bytes.value() == from_hex(kGoldenHex));

  auto decoded = hal::decode_notification(from_hex(kGoldenHex), key);
  REQUIRE(decoded.ok());
  CHECK(decoded->tag_ok);
  CHECK(decoded->wire.sender == "alpha");
  CHECK(decoded->wire.seq == 42);
  CHECK(decoded->wire.message == "at_door");
  CHECK(decoded->wire.recipients == std::vector<std::string>{"bravo", "charlie"});
  CHECK(decoded->wire.utime_us == 1700000000000000);
  CHECK_FALSE(decoded->wire.is_ack);
  CHECK(decoded->wire.session == golden_notification().session);
}

TEST_CASE("round trips of all three types keep every field and verify") {
  const auto key = test::fixed_key(7);
  NotificationWire ack;
  ack.utime_us = -5;
  ack.mission_id = "m";
  ack.sender = "bravo";
  ack.message = "at_door";
  ack.is_ack = true;
  ack.ack_sender = "alpha";
  ack.ack_seq = (std::uint64_t{1} << 63) - 1;
  auto a = hal::decode_notification(hal::encode_notification(ack, key).value(), key);
  REQUIRE(a.ok());
  CHECK(a->tag_ok);
  CHECK(a->wire.is_ack);
  CHECK(a->wire.ack_sender == "alpha");
  CHECK(a->wire.ack_seq == ack.ack_seq);
  CHECK(a->wire.recipients.empty());

  hal::StatusWire st;
  st.utime_us = 99;
  st.mission_id = "m";
  st.seq = 1234;
  st.status = {"bravo", "aborted", "GoToDoor", "p=0.42 below 0.9", 0.42};
  auto s = hal::decode_status(hal::encode_status(st, key).value(), key);
  REQUIRE(s.ok());
  CHECK(s->tag_ok);
  CHECK(s->wire.seq == 1234);
  CHECK(s->wire.status.robot == "bravo");
  CHECK(s->wire.status.phase == "aborted");
  CHECK(s->wire.status.state == "GoToDoor");
  CHECK(s->wire.status.reason == "p=0.42 below 0.9");
  CHECK(s->wire.status.p_success == doctest::Approx(0.42));

  hal::TelemetryWire tw;
  tw.mission_id = "m";
  tw.seq = 3;
  tw.telemetry = {"charlie", "Spin", 1.5, -2.25, 0.5, 0.3, -0.1, 1000, 2, 3, 850.0, 1900.0};
  auto t = hal::decode_telemetry(hal::encode_telemetry(tw, key).value(), key);
  REQUIRE(t.ok());
  CHECK(t->tag_ok);
  CHECK(t->wire.telemetry.robot == "charlie");
  CHECK(t->wire.telemetry.state == "Spin");
  CHECK(t->wire.telemetry.y_m == -2.25);
  CHECK(t->wire.telemetry.rot_vel_radps == -0.1);
  CHECK(t->wire.telemetry.cycles == 1000);
  CHECK(t->wire.telemetry.missed_updates == 3);
  CHECK(t->wire.telemetry.cycle_p99_us == 1900.0);
}

TEST_CASE("a wrong key, a flipped bit, a missing or short tag never verify") {
  const auto key = test::fixed_key(1);
  const auto good = from_hex(kGoldenHex);

  auto other_key = hal::decode_notification(good, test::fixed_key(2));
  REQUIRE(other_key.ok());
  CHECK_FALSE(other_key->tag_ok);

  // Flip one bit in every byte of the message body and of the tag in turn:
  // each copy is either malformed or fails verification, never accepted.
  for (std::size_t i = 0; i < good.size(); ++i) {
    auto bytes = good;
    bytes[i] ^= 0x01;
    auto d = hal::decode_notification(bytes, key);
    CHECK_MESSAGE(!(d.ok() && d->tag_ok), "byte " << i);
  }

  auto untagged = raw_notification();
  auto u = hal::decode_notification(encode_raw(untagged), key);
  REQUIRE(u.ok());
  CHECK_FALSE(u->tag_ok);

  auto short_tag = raw_notification();
  short_tag.tag_len = 16;
  short_tag.tag.assign(16, 0xAB);
  auto s = hal::decode_notification(encode_raw(short_tag), key);
  REQUIRE(s.ok());
  CHECK_FALSE(s->tag_ok);
}

TEST_CASE("malformed bytes are errors, never crashes: truncation, trailing bytes, bad lengths, wrong type") {
  const auto key = test::fixed_key(1);
  const auto good = from_hex(kGoldenHex);
  for (std::size_t n = 0; n < good.size(); ++n) {
    auto d = hal::decode_notification(std::span<const std::uint8_t>(good.data(), n), key);
    REQUIRE_FALSE(d.ok());
    CHECK(d.error().code == Error::Code::protocol);
  }
  auto longer = good;
  longer.push_back(0);
  CHECK_FALSE(hal::decode_notification(longer, key).ok());

  // A status decoder refuses a notification (fingerprint mismatch), and vice versa.
  CHECK_FALSE(hal::decode_status(good, key).ok());
  hal::StatusWire st;
  st.mission_id = "m";
  st.status.robot = "r";
  CHECK_FALSE(hal::decode_notification(hal::encode_status(st, key).value(), key).ok());

  // Hand-made lengths: the mission_id string length is at offset 16.
  auto set_i32 = [](std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
  };
  for (std::uint32_t bad_length : {0u, 0xFFFFFFFFu, 0x80000000u, 0x7FFFFFFFu, 1000u}) {
    auto b = good;
    set_i32(b, 16, bad_length);
    CHECK_FALSE(hal::decode_notification(b, key).ok());
  }
  // num_recipients negative / too many.
  auto neg = raw_notification();
  auto b = encode_raw(neg);
  // num_recipients sits right before "bravo"'s length (6) near the end: find it.
  const std::size_t recipients_at = b.size() - 2 /*tag_len*/ - 10 /*"bravo" string*/ - 2;
  REQUIRE(b[recipients_at] == 0);
  REQUIRE(b[recipients_at + 1] == 1);
  b[recipients_at] = 0xFF;  // -255
  CHECK_FALSE(hal::decode_notification(b, key).ok());

  // A NUL inside a string (lcm-gen's encoder cannot even produce one: patch the bytes).
  auto with_x = raw_notification();
  with_x.message = "gxo";
  auto nul_bytes = encode_raw(with_x);
  REQUIRE(hal::decode_notification(nul_bytes, key).ok());
  const auto x_at = std::find(nul_bytes.begin(), nul_bytes.end(), std::uint8_t{'x'});
  REQUIRE(x_at != nul_bytes.end());
  *x_at = 0;
  CHECK_FALSE(hal::decode_notification(nul_bytes, key).ok());

  auto bad_bool = raw_notification();
  bad_bool.is_ack = 2;
  CHECK_FALSE(hal::decode_notification(encode_raw(bad_bool), key).ok());

  auto negative_seq = raw_notification();
  negative_seq.seq = -1;
  CHECK_FALSE(hal::decode_notification(encode_raw(negative_seq), key).ok());

  auto too_long = raw_notification();
  too_long.sender = std::string(hal::kMaxTeamNameBytes + 1, 'x');
  CHECK_FALSE(hal::decode_notification(encode_raw(too_long), key).ok());
}

TEST_CASE("encoders refuse fields beyond the limits, with a message naming the field") {
  const auto key = test::fixed_key(1);
  auto w = golden_notification();
  w.message = std::string(hal::kMaxTeamMessageBytes + 1, 'm');
  auto e = hal::encode_notification(w, key);
  REQUIRE_FALSE(e.ok());
  CHECK(e.error().code == Error::Code::invalid_argument);
  CHECK(e.error().message.find("message") != std::string::npos);

  w = golden_notification();
  w.recipients.assign(hal::kMaxTeamRecipients + 1, "bravo");
  CHECK_FALSE(hal::encode_notification(w, key).ok());

  w = golden_notification();
  w.seq = std::uint64_t{1} << 63;
  CHECK_FALSE(hal::encode_notification(w, key).ok());

  hal::StatusWire st;
  st.mission_id = "m";
  st.status.robot = "r";
  st.status.p_success = std::nan("");
  auto s = hal::encode_status(st, key);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("p_success") != std::string::npos);
}

TEST_CASE("channel names are LCM's and map both ways") {
  CHECK(hal::channel_name(hal::TeamChannel::notify) == "P3AT_NOTIFY");
  CHECK(hal::channel_name(hal::TeamChannel::telemetry) == "P3AT_TELEMETRY");
  CHECK(hal::channel_name(hal::TeamChannel::status) == "P3AT_STATUS");
  for (auto c : {hal::TeamChannel::notify, hal::TeamChannel::telemetry, hal::TeamChannel::status}) {
    CHECK(hal::channel_from_name(hal::channel_name(c)) == c);
  }
  CHECK_FALSE(hal::channel_from_name("P3AT_OTHER").has_value());
}
