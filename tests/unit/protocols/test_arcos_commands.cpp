// ARCOS commands: integer, string and VEL2 arguments, encoded and decoded.

#include <doctest/doctest.h>

#include <climits>
#include <string>

#include "arcos_test_util.hpp"
#include "p3at/protocols/arcos/commands.hpp"

using namespace p3at::arcos;
using namespace p3at::arcos::test;

namespace {

constexpr Command kAllCommands[] = {
    Command::pulse, Command::open,   Command::close,  Command::polling,   Command::enable,   Command::seta,
    Command::setv,  Command::seto,   Command::move,   Command::rotate,    Command::setrv,    Command::vel,
    Command::head,  Command::dhead,  Command::say,    Command::config,    Command::encoder,  Command::rvel,
    Command::setra, Command::sonar,  Command::stop,   Command::vel2,      Command::bumpstall, Command::hostbaud,
    Command::estop, Command::gyro,   Command::batteryinfo, Command::reset,
};

// Integer arguments only: a string argument points into the packet, which this drops.
DecodedCommand round_trip(const Frame& frame) { return decode_command(to_packet(frame)); }

}  // namespace

TEST_CASE("no-argument commands round trip as kind none") {
  for (Command c : kAllCommands) {
    const Frame f = encode_command(c);
    CHECK(f.size == 6);
    const DecodedCommand d = round_trip(f);
    CHECK(d.number == static_cast<std::uint8_t>(c));
    CHECK(d.kind == DecodedCommand::ArgKind::none);
    CHECK(d.value == 0);
  }
}

TEST_CASE("integer arguments round trip for every command, both signs") {
  const int values[] = {0, 1, -1, 2, 300, -20, 255, 256, -256, 32767, -32768, 65535, -65535};
  for (Command c : kAllCommands) {
    for (int v : values) {
      CAPTURE(command_name(static_cast<std::uint8_t>(c)));
      CAPTURE(v);
      const Frame f = encode_command(c, v);
      REQUIRE(f.size == 9);
      CHECK(f.bytes[2] == 6);
      CHECK(f.bytes[4] == (v < 0 ? kArgNegative : kArgPositive));
      const DecodedCommand d = round_trip(f);
      CHECK(d.number == static_cast<std::uint8_t>(c));
      CHECK(d.kind == DecodedCommand::ArgKind::integer);
      CHECK(d.value == v);
    }
  }
}

TEST_CASE("integer magnitude is little-endian and saturates at 65535") {
  const Frame f = encode_command(Command::move, -0x1234);
  CHECK(f.bytes[4] == 0x1B);
  CHECK(f.bytes[5] == 0x34);
  CHECK(f.bytes[6] == 0x12);
  CHECK(round_trip(encode_command(Command::move, 70000)).value == 65535);
  CHECK(round_trip(encode_command(Command::move, -70000)).value == -65535);
  CHECK(round_trip(encode_command(Command::move, INT_MAX)).value == 65535);
  CHECK(round_trip(encode_command(Command::move, INT_MIN)).value == -65535);
}

TEST_CASE("string arguments: type 0x2B, length, characters, uncounted zero") {
  const Frame f = encode_command(Command::say, std::string_view("abc"));
  CHECK(to_bytes(f).size() == 3 + 1 + 6 + 2);
  CHECK(f.bytes[2] == 3 + 6);
  CHECK(f.bytes[3] == 15);
  CHECK(f.bytes[4] == kArgString);
  CHECK(f.bytes[5] == 3);
  CHECK(f.bytes[6] == 'a');
  CHECK(f.bytes[7] == 'b');
  CHECK(f.bytes[8] == 'c');
  CHECK(f.bytes[9] == 0);
  const Packet p = to_packet(f);
  const DecodedCommand d = decode_command(p);
  CHECK(d.kind == DecodedCommand::ArgKind::string);
  CHECK(d.text == "abc");

  const Packet empty_packet = to_packet(encode_command(Command::polling, std::string_view{}));
  const DecodedCommand empty = decode_command(empty_packet);
  CHECK(empty.kind == DecodedCommand::ArgKind::string);
  CHECK(empty.text.empty());

  // Binary characters survive (POLLING sends sonar numbers as bytes).
  const std::string order("\x01\x02\x03\x00\x04", 5);
  const Packet poll_packet = to_packet(encode_command(Command::polling, order));
  const DecodedCommand poll = decode_command(poll_packet);
  CHECK(poll.text == order);
}

TEST_CASE("string arguments longer than 200 characters are cut to 200") {
  const std::string longer(250, 'x');
  const Frame f = encode_command(Command::say, longer);
  CHECK(f.bytes[5] == 200);
  CHECK(f.size == 3 + 1 + 2 + 200 + 1 + 2);
  const Packet p = to_packet(f);
  const DecodedCommand d = decode_command(p);
  CHECK(d.text == std::string(200, 'x'));
}

TEST_CASE("decode_command flags malformed arguments") {
  SUBCASE("integer with one magnitude byte") {
    const DecodedCommand d = decode_command(make_packet(11, bytes({0x3B, 0x05})));
    CHECK(d.number == 11);
    CHECK(d.kind == DecodedCommand::ArgKind::malformed);
  }
  SUBCASE("negative integer with no magnitude") {
    CHECK(decode_command(make_packet(21, bytes({0x1B}))).kind == DecodedCommand::ArgKind::malformed);
  }
  SUBCASE("string without length byte") {
    CHECK(decode_command(make_packet(15, bytes({0x2B}))).kind == DecodedCommand::ArgKind::malformed);
  }
  SUBCASE("string length past the payload") {
    CHECK(decode_command(make_packet(15, bytes({0x2B, 4, 'a', 'b', 'c'}))).kind ==
          DecodedCommand::ArgKind::malformed);
  }
  SUBCASE("unknown argument type byte") {
    CHECK(decode_command(make_packet(11, bytes({0x42, 1, 0}))).kind == DecodedCommand::ArgKind::malformed);
  }
}

TEST_CASE("decode_command ignores extra bytes after an argument") {
  const DecodedCommand i = decode_command(make_packet(1, bytes({0x3B, 0x01, 0x00, 0xDE, 0xAD})));
  CHECK(i.kind == DecodedCommand::ArgKind::integer);
  CHECK(i.value == 1);
  const DecodedCommand n = decode_command(make_packet(55, bytes({0x1B, 0x02, 0x00, 0x3B})));
  CHECK(n.kind == DecodedCommand::ArgKind::integer);
  CHECK(n.value == -2);
  const Packet sp = make_packet(15, bytes({0x2B, 2, 'h', 'i', 0, 0x99}));
  const DecodedCommand s = decode_command(sp);
  CHECK(s.kind == DecodedCommand::ArgKind::string);
  CHECK(s.text == "hi");
  // Unknown command numbers decode too; the robot decides to ignore them.
  const DecodedCommand u = decode_command(make_packet(200, bytes({0x3B, 7, 0})));
  CHECK(u.number == 200);
  CHECK(u.value == 7);
}

TEST_CASE("decoded string points into the packet") {
  const Packet p = make_packet(15, bytes({0x2B, 2, 'o', 'k'}));
  const DecodedCommand d = decode_command(p);
  CHECK(static_cast<const void*>(d.text.data()) == static_cast<const void*>(p.payload_bytes.data() + 2));
}

TEST_CASE("VEL2 packs left high, right low, and round trips every pair") {
  for (int left = -128; left <= 127; ++left) {
    for (int right = -128; right <= 127; ++right) {
      const DecodedCommand d = round_trip(encode_vel2(left, right));
      REQUIRE(d.kind == DecodedCommand::ArgKind::integer);
      REQUIRE(d.number == 32);
      REQUIRE((d.value & 0xFFFF) == (((left & 0xFF) << 8) | (right & 0xFF)));
      const Vel2 v = unpack_vel2(d.value);
      REQUIRE(v.left_units == left);
      REQUIRE(v.right_units == right);
    }
  }
}

TEST_CASE("VEL2 clamps each wheel to -128..127") {
  const Vel2 v = unpack_vel2(round_trip(encode_vel2(500, -500)).value);
  CHECK(v.left_units == 127);
  CHECK(v.right_units == -128);
  const Vel2 w = unpack_vel2(round_trip(encode_vel2(-129, 128)).value);
  CHECK(w.left_units == -128);
  CHECK(w.right_units == 127);
}

TEST_CASE("unpack_vel2 of values a robot may see") {
  CHECK(unpack_vel2(0).left_units == 0);
  CHECK(unpack_vel2(0x0A0A).left_units == 10);
  CHECK(unpack_vel2(0x0A0A).right_units == 10);
  CHECK(unpack_vel2(-2550).left_units == -10);
  CHECK(unpack_vel2(-2550).right_units == 10);
  // The unsigned spelling of the same 16 bits gives the same wheels.
  CHECK(unpack_vel2(0xF60A).left_units == -10);
  CHECK(unpack_vel2(0xF60A).right_units == 10);
}

TEST_CASE("command_name") {
  CHECK(std::string(command_name(11)) == "VEL");
  CHECK(std::string(command_name(21)) == "RVEL");
  CHECK(std::string(command_name(32)) == "VEL2");
  CHECK(std::string(command_name(253)) == "RESET");
  CHECK(std::string(command_name(14)) == "UNKNOWN");
  CHECK(std::string(command_name(254)) == "UNKNOWN");
  for (Command c : kAllCommands) CHECK(std::string(command_name(static_cast<std::uint8_t>(c))) != "UNKNOWN");
  // Names are unique.
  for (Command a : kAllCommands)
    for (Command b : kAllCommands)
      if (a != b)
        CHECK(std::string(command_name(static_cast<std::uint8_t>(a))) !=
              std::string(command_name(static_cast<std::uint8_t>(b))));
}
