// The CONFIG reply, packet 0x20: field order, round trips, truncation, simulator values.

#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "arcos_test_util.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"
#include "p3at/protocols/arcos/sip.hpp"

using namespace p3at::arcos;
using namespace p3at::arcos::test;

namespace {

constexpr int kConfigFields = 48;

// Every field distinct, so a swapped pair of fields shows up.
ConfigPacket sample_config() {
  ConfigPacket c;
  c.robot_class = "Pioneer";
  c.subclass = "p3at";
  c.serial_number = "SN42";
  c.spare = 0xA5;
  c.top_rot_vel = 0x0101;
  c.top_trans_vel = 0x0202;
  c.top_rot_accel = 0x0303;
  c.top_trans_accel = 0x0404;
  c.max_pwm = 0x0505;
  c.name = "alpha";
  c.sip_cycle_ms = 6;
  c.host_baud = 7;
  c.aux_baud = 8;
  c.gripper = 0x0909;
  c.front_sonar = 0x0A0A;
  c.rear_sonar = 11;
  c.low_battery = 0x0C0C;
  c.revcount = 0x0D0D;
  c.watchdog_ms = 0x0E0E;
  c.flag_byte = 15;
  c.stall_pwm = 0x1010;
  c.stall_time = 0x1111;
  c.joy_trans_vel = 0x1212;
  c.joy_rot_vel = 0x1313;
  c.rot_vel_max = 0x1414;
  c.trans_vel_max = 0x1515;
  c.rot_accel = 0x1616;
  c.rot_decel = 0x1717;
  c.rot_kp = 0x1818;
  c.rot_kv = 0x1919;
  c.rot_ki = 0x1A1A;
  c.trans_accel = 0x1B1B;
  c.trans_decel = 0x1C1C;
  c.trans_kp = 0x1D1D;
  c.trans_kv = 0x1E1E;
  c.trans_ki = 0x1F1F;
  c.front_bumpers = 32;
  c.rear_bumpers = 33;
  c.charger_type = 34;
  c.sonar_cycle = 35;
  c.auto_baud = 2;
  c.gyro_type = 37;
  c.drift_factor = -1234;
  c.aux2_baud = 38;
  c.aux3_baud = 39;
  c.ticks_per_mm = 0x2828;
  c.shutdown_voltage = 0x2929;
  c.firmware_version = "ARCOS 1.9";
  return c;
}

// Where each field of the sample payload ends, and whether it is a string.
struct FieldEnd {
  std::size_t end;
  bool is_string;
};

// The payload of sample_config(), spelled out from the field list of §6.
Bytes sample_payload(std::vector<FieldEnd>* ends = nullptr) {
  Bytes p;
  const auto mark = [&](bool is_string) {
    if (ends != nullptr) ends->push_back({p.size(), is_string});
  };
  const auto str = [&](std::string_view s) {
    append(p, s);
    p.push_back(0);
    mark(true);
  };
  const auto u8 = [&](int v) {
    p.push_back(static_cast<std::uint8_t>(v));
    mark(false);
  };
  const auto u16 = [&](int v) {
    p.push_back(static_cast<std::uint8_t>(v & 0xFF));
    p.push_back(static_cast<std::uint8_t>((v >> 8) & 0xFF));
    mark(false);
  };
  str("Pioneer");
  str("p3at");
  str("SN42");
  u8(0xA5);
  for (int v = 1; v <= 5; ++v) u16(v * 0x0101);  // top rot vel .. max PWM
  str("alpha");
  u8(6);
  u8(7);
  u8(8);
  u16(0x0909);
  u16(0x0A0A);
  u8(11);
  u16(0x0C0C);
  u16(0x0D0D);
  u16(0x0E0E);
  u8(15);
  for (int v = 0x10; v <= 0x1F; ++v) u16(v * 0x0101);  // stall PWM .. trans KI
  for (int v : {32, 33, 34, 35, 2, 37}) u8(v);
  u16(-1234 & 0xFFFF);
  u8(38);
  u8(39);
  u16(0x2828);
  u16(0x2929);
  str("ARCOS 1.9");
  return p;
}

}  // namespace

TEST_CASE("config: encoding follows the field order of the doc byte for byte") {
  const Frame f = encode_config(sample_config());
  CHECK(f.bytes[3] == kConfigPacket);
  const Packet p = to_packet(f);
  CHECK(Bytes(p.payload().begin(), p.payload().end()) == sample_payload());
}

TEST_CASE("config: round trip reads all fields") {
  int fields = -1;
  const ConfigPacket out = decode_config(to_packet(encode_config(sample_config())), &fields);
  CHECK(out == sample_config());
  CHECK(fields == kConfigFields);
  // fields_read is optional.
  CHECK(decode_config(to_packet(encode_config(sample_config()))) == sample_config());
}

TEST_CASE("config: default (all zero, empty) config round trips") {
  int fields = -1;
  const ConfigPacket out = decode_config(to_packet(encode_config(ConfigPacket{})), &fields);
  CHECK(out == ConfigPacket{});
  CHECK(fields == kConfigFields);
}

TEST_CASE("config: every truncation is tolerated, missing fields read as 0 / empty") {
  std::vector<FieldEnd> ends;
  const Bytes full = sample_payload(&ends);
  REQUIRE(ends.size() == kConfigFields);
  for (std::size_t n = 0; n <= full.size(); ++n) {
    CAPTURE(n);
    // The fields wholly inside the first n bytes, and where the last of them ends.
    int whole = 0;
    std::size_t boundary = 0;
    while (whole < kConfigFields && ends[static_cast<std::size_t>(whole)].end <= n) {
      boundary = ends[static_cast<std::size_t>(whole)].end;
      ++whole;
    }
    int fields = -1;
    const ConfigPacket out = decode_config(make_packet(kConfigPacket, std::span(full).first(n)), &fields);
    CHECK(fields == whole);
    // Re-encoded, the whole fields give the original bytes; after them comes the
    // part of a cut string (if the cut is inside one), then nothing but zeros.
    const Packet again = to_packet(encode_config(out));
    const auto bytes_again = again.payload();
    REQUIRE(bytes_again.size() >= boundary);
    CHECK(Bytes(bytes_again.begin(), bytes_again.begin() + static_cast<std::ptrdiff_t>(boundary)) ==
          Bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(boundary)));
    std::size_t zeros_from = boundary;
    if (whole < kConfigFields && ends[static_cast<std::size_t>(whole)].is_string) zeros_from = n;
    CHECK(Bytes(bytes_again.begin() + static_cast<std::ptrdiff_t>(boundary),
                bytes_again.begin() + static_cast<std::ptrdiff_t>(zeros_from)) ==
          Bytes(full.begin() + static_cast<std::ptrdiff_t>(boundary), full.begin() + static_cast<std::ptrdiff_t>(zeros_from)));
    CHECK(std::all_of(bytes_again.begin() + static_cast<std::ptrdiff_t>(zeros_from), bytes_again.end(),
                      [](std::uint8_t b) { return b == 0; }));
  }
}

TEST_CASE("config: specific truncation points") {
  const Packet full = to_packet(encode_config(sample_config()));
  int fields = -1;

  ConfigPacket out = decode_config(make_packet(kConfigPacket, {}), &fields);
  CHECK(fields == 0);
  CHECK(out == ConfigPacket{});

  // "Pioneer\0p3at\0SN42\0" then the spare byte and one byte of top_rot_vel.
  out = decode_config(make_packet(kConfigPacket, full.payload().first(20)), &fields);
  CHECK(fields == 4);
  CHECK(out.serial_number == "SN42");
  CHECK(out.spare == 0xA5);
  CHECK(out.top_rot_vel == 0);
  CHECK(out.name.empty());
  CHECK(out.trans_vel_max == 0);

  // A string cut before its terminator is kept as far as it goes but not counted.
  out = decode_config(make_packet(kConfigPacket, full.payload().first(3)), &fields);
  CHECK(fields == 0);
  CHECK(out.robot_class == "Pio");
  CHECK(out.subclass.empty());

  // Everything but the firmware version's terminator.
  out = decode_config(make_packet(kConfigPacket, full.payload().first(full.payload_size - 1u)), &fields);
  CHECK(fields == kConfigFields - 1);
  CHECK(out.firmware_version == "ARCOS 1.9");
  CHECK(out.shutdown_voltage == 0x2929);
}

TEST_CASE("config: extra bytes from newer firmware are ignored") {
  Bytes payload = sample_payload();
  append(payload, bytes({1, 2, 3, 4}));
  int fields = -1;
  CHECK(decode_config(make_packet(kConfigPacket, payload), &fields) == sample_config());
  CHECK(fields == kConfigFields);
}

TEST_CASE("config: over-long strings are cut so the frame always fits") {
  ConfigPacket c = sample_config();
  c.robot_class = std::string(300, 'a');
  c.subclass = std::string(300, 'b');
  c.serial_number = std::string(300, 'c');
  c.name = std::string(300, 'd');
  c.firmware_version = std::string(300, 'e');
  const Frame f = encode_config(c);
  CHECK(f.size <= kMaxFrame);
  int fields = -1;
  const ConfigPacket out = decode_config(to_packet(f), &fields);
  CHECK(fields == kConfigFields);
  CHECK(out.robot_class == std::string(32, 'a'));
  CHECK(out.firmware_version == std::string(32, 'e'));
  CHECK(out.shutdown_voltage == c.shutdown_voltage);
}

TEST_CASE("config: what a simulator answers") {
  const ConfigPacket c = simulator_config("robot-3", "p3at-sh");
  CHECK(c.robot_class == "Pioneer");
  CHECK(c.subclass == "p3at-sh");
  CHECK(c.serial_number == "SIM");
  CHECK(c.name == "robot-3");
  CHECK(c.sip_cycle_ms == 100);
  CHECK(c.watchdog_ms == 2000);
  CHECK(c.trans_vel_max == 3000);
  CHECK(c.rot_vel_max == 150);
  CHECK(c.trans_accel == 300);
  CHECK(c.trans_decel == 300);
  CHECK(c.rot_accel == 100);
  CHECK(c.rot_decel == 100);
  // Top values must not be below the current maxima, or a client would clamp them.
  CHECK(c.top_trans_vel >= c.trans_vel_max);
  CHECK(c.top_rot_vel >= c.rot_vel_max);
  CHECK(c.top_trans_accel >= c.trans_accel);
  CHECK(c.top_rot_accel >= c.rot_accel);
  int fields = -1;
  CHECK(decode_config(to_packet(encode_config(c)), &fields) == c);
  CHECK(fields == kConfigFields);
}
