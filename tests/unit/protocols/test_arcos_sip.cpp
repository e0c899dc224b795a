// SIPs, the SYNC2 identity, odometry wraps and per-model parameters.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <random>
#include <string>

#include "arcos_test_util.hpp"
#include "p3at/protocols/arcos/sip.hpp"

using namespace p3at::arcos;
using namespace p3at::arcos::test;

namespace {

// A SIP with every mandatory field distinct and three sonar readings.
Sip base_sip() {
  Sip s;
  s.moving = true;
  s.xpos = 0x1234;
  s.ypos = 0x2345;
  s.thpos = -1024;
  s.left_vel = -300;
  s.right_vel = 301;
  s.battery = 128;
  s.stall_bumpers = kLeftStall | kRightStall | 0x0200;
  s.control = 2047;
  s.flags = kFlagMotorsEnabled | kFlagEstop;
  s.compass = 90;
  s.sonar_count = 3;
  s.sonar[0] = {0, 5000};
  s.sonar[1] = {7, 0x0102};
  s.sonar[2] = {15, 0xFFFF};
  return s;
}

// base_sip() with the first `groups` optional groups present.
Sip with_groups(int groups) {
  Sip s = base_sip();
  if (groups > 0) s.io = SipIo{1, 2, 3, 4, 5};
  if (groups > 1) s.battery_x10 = 131;
  if (groups > 2) s.charge_state = 2;
  if (groups > 3) s.rotvel = -455;
  if (groups > 4) s.fault_flags = 0x001A;
  if (groups > 5) s.latvel = -7;
  if (groups > 6) s.temperature = -127;
  if (groups > 7) s.state_of_charge = 88;
  if (groups > 8) s.controller_time_us = 0xDEADBEEF;
  if (groups > 9) s.flags3 = 0x80000001;
  return s;
}

// Payload sizes of the optional groups, in wire order.
constexpr std::size_t kGroupBytes[] = {5, 2, 1, 2, 2, 2, 1, 1, 4, 4};

std::uint16_t u16_at(const Frame& f, std::size_t off) { return get_u16_le(f.bytes.data() + off); }

}  // namespace

TEST_CASE("SIP: mandatory fields sit at the documented offsets from 0xFA") {
  const Frame f = encode_sip(base_sip());
  CHECK(f.bytes[3] == kSipMoving);
  CHECK(u16_at(f, 4) == 0x1234);
  CHECK(u16_at(f, 6) == 0x2345);
  CHECK(static_cast<std::int16_t>(u16_at(f, 8)) == -1024);
  CHECK(static_cast<std::int16_t>(u16_at(f, 10)) == -300);
  CHECK(static_cast<std::int16_t>(u16_at(f, 12)) == 301);
  CHECK(f.bytes[14] == 128);
  CHECK(u16_at(f, 15) == 0x0301);
  CHECK(u16_at(f, 17) == 2047);
  CHECK(u16_at(f, 19) == 0x0021);
  CHECK(f.bytes[21] == 90);
  CHECK(f.bytes[22] == 3);
  CHECK(f.bytes[23] == 0);
  CHECK(u16_at(f, 24) == 5000);
  CHECK(f.bytes[26] == 7);
  CHECK(u16_at(f, 27) == 0x0102);
  CHECK(f.bytes[29] == 15);
  CHECK(u16_at(f, 30) == 0xFFFF);
  CHECK(f.size == 32 + 2);  // checksum right after the sonar block
  CHECK(f.bytes[2] == f.size - 3);

  Sip stopped = base_sip();
  stopped.moving = false;
  CHECK(encode_sip(stopped).bytes[3] == kSipStopped);
}

TEST_CASE("SIP: optional groups sit at the documented offsets after the sonar block") {
  const Frame f = encode_sip(with_groups(10));
  const std::size_t b = 32;  // first byte after 3 sonar readings
  CHECK(f.bytes[b + 0] == 1);
  CHECK(f.bytes[b + 1] == 2);
  CHECK(f.bytes[b + 2] == 3);
  CHECK(f.bytes[b + 3] == 4);
  CHECK(f.bytes[b + 4] == 5);
  CHECK(u16_at(f, b + 5) == 131);
  CHECK(f.bytes[b + 7] == 2);
  CHECK(static_cast<std::int16_t>(u16_at(f, b + 8)) == -455);
  CHECK(u16_at(f, b + 10) == 0x001A);
  CHECK(static_cast<std::int16_t>(u16_at(f, b + 12)) == -7);
  CHECK(static_cast<std::int8_t>(f.bytes[b + 14]) == -127);
  CHECK(f.bytes[b + 15] == 88);
  CHECK(u16_at(f, b + 16) == 0xBEEF);
  CHECK(u16_at(f, b + 18) == 0xDEAD);
  CHECK(u16_at(f, b + 20) == 0x0001);
  CHECK(u16_at(f, b + 22) == 0x8000);
  CHECK(f.size == b + 24 + 2);
}

TEST_CASE("SIP: round trip with 0..10 optional groups") {
  std::size_t expected_payload = 19 + 3 * 3;
  for (int groups = 0; groups <= 10; ++groups) {
    CAPTURE(groups);
    if (groups > 0) expected_payload += kGroupBytes[groups - 1];
    const Sip in = with_groups(groups);
    const Frame f = encode_sip(in);
    CHECK(f.size == expected_payload + 6);
    const auto out = decode_sip(to_packet(f));
    REQUIRE(out.ok());
    CHECK(*out == in);
    CHECK(out->io.has_value() == (groups > 0));
    CHECK(out->flags3.has_value() == (groups > 9));
  }
}

TEST_CASE("SIP: encoding stops at the first absent group") {
  Sip s = with_groups(10);
  s.charge_state.reset();  // groups after it are present but must not be sent
  const auto out = decode_sip(to_packet(encode_sip(s)));
  REQUIRE(out.ok());
  CHECK(*out == with_groups(2));
  CHECK(!out->rotvel.has_value());

  Sip no_io = with_groups(10);
  no_io.io.reset();
  CHECK(encode_sip(no_io).size == encode_sip(base_sip()).size);
}

TEST_CASE("SIP: a partial group is not read") {
  // Payloads cut 0..8 bytes short of three whole groups (5 + 2 + 1 bytes).
  const Packet full = to_packet(encode_sip(with_groups(3)));
  for (std::size_t cut = 0; cut <= 8; ++cut) {
    CAPTURE(cut);
    const Packet p = make_packet(full.id, full.payload().first(full.payload_size - cut));
    const auto out = decode_sip(p);
    REQUIRE(out.ok());
    const std::size_t extra = std::size_t{p.payload_size} - 28;  // bytes after the sonar block
    CHECK(out->io.has_value() == (extra >= 5));
    CHECK(out->battery_x10.has_value() == (extra >= 7));
    CHECK(out->charge_state.has_value() == (extra >= 8));
    CHECK(out->xpos == 0x1234);
  }
}

TEST_CASE("SIP: no sonar readings, and the most the struct holds") {
  Sip none = with_groups(4);
  none.sonar_count = 0;
  auto out = decode_sip(to_packet(encode_sip(none)));
  REQUIRE(out.ok());
  CHECK(*out == none);

  Sip many = with_groups(10);
  many.sonar_count = 32;
  for (std::uint8_t i = 0; i < 32; ++i) many.sonar[i] = {i, static_cast<std::uint16_t>(1000 + i)};
  out = decode_sip(to_packet(encode_sip(many)));
  REQUIRE(out.ok());
  CHECK(*out == many);
}

TEST_CASE("SIP: equality ignores unused sonar slots but not used ones") {
  Sip a = base_sip();
  Sip b = base_sip();
  b.sonar[10] = {9, 9};
  CHECK(a == b);
  b.sonar[2].range = 1;
  CHECK(!(a == b));
  Sip c = with_groups(3);
  CHECK(!(a == c));
}

TEST_CASE("SIP: errors for a wrong id, a short packet or a short sonar block") {
  const Packet good = to_packet(encode_sip(base_sip()));

  SUBCASE("wrong id") {
    Packet p = good;
    p.id = 0x20;
    const auto out = decode_sip(p);
    REQUIRE(!out.ok());
    CHECK(out.error().code == p3at::Error::Code::protocol);
    CHECK(out.error().message.find("type") != std::string::npos);
  }
  SUBCASE("too short for the mandatory fields") {
    for (std::size_t n = 0; n < 19; ++n) {
      const auto out = decode_sip(make_packet(kSipStopped, good.payload().first(n)));
      REQUIRE(!out.ok());
      CHECK(out.error().code == p3at::Error::Code::protocol);
      CHECK(out.error().message.find("mandatory") != std::string::npos);
    }
  }
  SUBCASE("sonar block cut short") {
    for (std::size_t n = 19; n < 28; ++n) {
      const auto out = decode_sip(make_packet(kSipMoving, good.payload().first(n)));
      REQUIRE(!out.ok());
      CHECK(out.error().code == p3at::Error::Code::protocol);
      CHECK(out.error().message.find("sonar") != std::string::npos);
    }
  }
  SUBCASE("more sonar readings than a SIP holds") {
    std::array<std::uint8_t, 19 + 33 * 3> payload{};
    std::copy_n(good.payload().begin(), 19, payload.begin());
    payload[18] = 33;
    const auto out = decode_sip(make_packet(kSipMoving, payload));
    REQUIRE(!out.ok());
    CHECK(out.error().message.find("33") != std::string::npos);
  }
}

TEST_CASE("identity: round trip, and missing terminators tolerated") {
  const RobotIdentity in{"robot-7", "Pioneer", "p3at-sh"};
  const RobotIdentity out = decode_identity(to_packet(encode_identity(in)));
  CHECK(out.name == in.name);
  CHECK(out.robot_class == in.robot_class);
  CHECK(out.subclass == in.subclass);

  Bytes payload;
  append(payload, std::string_view("Sim\0Pioneer\0p3a", 15));
  const RobotIdentity cut = decode_identity(make_packet(2, payload));
  CHECK(cut.name == "Sim");
  CHECK(cut.robot_class == "Pioneer");
  CHECK(cut.subclass == "p3a");

  const RobotIdentity empty = decode_identity(make_packet(2, {}));
  CHECK(empty.name.empty());
  CHECK(empty.robot_class.empty());
  CHECK(empty.subclass.empty());

  Bytes one;
  append(one, std::string_view("OnlyName"));
  const RobotIdentity only = decode_identity(make_packet(2, one));
  CHECK(only.name == "OnlyName");
  CHECK(only.subclass.empty());
}

TEST_CASE("identity: over-long strings are cut so the frame fits") {
  const RobotIdentity in{std::string(300, 'n'), std::string(300, 'c'), std::string(300, 's')};
  const Frame f = encode_identity(in);
  CHECK(f.size <= kMaxFrame);
  const RobotIdentity out = decode_identity(to_packet(f));
  CHECK(out.name == std::string(80, 'n'));
  CHECK(out.robot_class == std::string(80, 'c'));
  CHECK(out.subclass == std::string(80, 's'));
}

TEST_CASE("wrap_delta_15bit: plain steps and wraps in both directions") {
  CHECK(wrap_delta_15bit(100, 200) == 100);
  CHECK(wrap_delta_15bit(200, 100) == -100);
  CHECK(wrap_delta_15bit(0x7FF0, 0x0010) == 0x20);    // forward through the wrap
  CHECK(wrap_delta_15bit(0x0010, 0x7FF0) == -0x20);   // backward through the wrap
  CHECK(wrap_delta_15bit(0x7FFF, 0x0000) == 1);
  CHECK(wrap_delta_15bit(0x0000, 0x7FFF) == -1);
  CHECK(wrap_delta_15bit(0, 0x1000) == 0x1000);       // exactly 0x1000 is not a wrap
  CHECK(wrap_delta_15bit(0x1000, 0) == -0x1000);
  CHECK(wrap_delta_15bit(0, 0x1001) == 0x1001 - 0x8000);
  CHECK(wrap_delta_15bit(0x1001, 0) == 0x8000 - 0x1001);
  CHECK(wrap_delta_15bit(0x8005, 0x0005) == 0);       // bit 15 is not part of the counter
  CHECK(wrap_delta_15bit(0x0005, 0xFFFF) == -6);
}

TEST_CASE("wrap_delta_15bit: accumulated deltas track a long drive both ways") {
  std::mt19937 rng(99);
  // Steps stay under the 0x1000 wrap threshold, drift included.
  std::uniform_int_distribution<int> step(-0x0B00, 0x0B00);
  long long truth = 0;
  long long tracked = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto previous = static_cast<std::uint16_t>(truth & 0x7FFF);
    // Drift forward for a while, then backward, crossing the wrap many times.
    truth += step(rng) + (i < 10000 ? 900 : -900);
    const auto current = static_cast<std::uint16_t>(truth & 0x7FFF);
    tracked += wrap_delta_15bit(previous, current);
  }
  CHECK(tracked == truth);
}

TEST_CASE("wrap_delta_heading: 4096 per turn, result in (-2048, 2048]") {
  CHECK(wrap_delta_heading(0, 100) == 100);
  CHECK(wrap_delta_heading(4000, 100) == 196);
  CHECK(wrap_delta_heading(100, 4000) == -196);
  CHECK(wrap_delta_heading(-2000, 2000) == -96);
  CHECK(wrap_delta_heading(2000, -2000) == 96);
  CHECK(wrap_delta_heading(0, 2048) == 2048);
  CHECK(wrap_delta_heading(0, -2048) == 2048);
  CHECK(wrap_delta_heading(0, 2049) == -2047);
  CHECK(wrap_delta_heading(0, 4096) == 0);
  CHECK(wrap_delta_heading(-32768, 32767) == -1);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> any(-32768, 32767);
  for (int i = 0; i < 10000; ++i) {
    const auto a = static_cast<std::int16_t>(any(rng));
    const auto b = static_cast<std::int16_t>(any(rng));
    const int d = wrap_delta_heading(a, b);
    REQUIRE(d > -2048);
    REQUIRE(d <= 2048);
    REQUIRE(((a + d - b) % 4096 + 4096) % 4096 == 0);
  }
}

TEST_CASE("RobotParams::for_subclass") {
  CHECK(RobotParams::for_subclass("p3at").dist_conv == doctest::Approx(0.465));
  CHECK(RobotParams::for_subclass("P3AT").dist_conv == doctest::Approx(0.465));
  CHECK(RobotParams::for_subclass("p3at-sh").dist_conv == doctest::Approx(1.0));
  CHECK(RobotParams::for_subclass("p3dx").dist_conv == doctest::Approx(1.0));
  CHECK(RobotParams::for_subclass("").dist_conv == doctest::Approx(1.0));
  const RobotParams p = RobotParams::for_subclass("p3at");
  CHECK(p.vel_conv == doctest::Approx(1.0));
  CHECK(p.range_conv == doctest::Approx(1.0));
  CHECK(p.diff_conv == doctest::Approx(0.0034));
  CHECK(p.angle_conv * 4096 == doctest::Approx(2 * 3.14159265358979323846));
  CHECK(p.vel2_divisor == 20);
}
