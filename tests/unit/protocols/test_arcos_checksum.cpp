// ARCOS framing and checksum: every known answer of docs/arcos-protocol.md §1.

#include <doctest/doctest.h>

#include "arcos_test_util.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/packet.hpp"
#include "p3at/protocols/arcos/sip.hpp"

using namespace p3at::arcos;
using namespace p3at::arcos::test;

namespace {

// The checksum the frame carries, high byte first.
std::uint16_t wire_checksum(const Bytes& frame) {
  return static_cast<std::uint16_t>((frame[frame.size() - 2] << 8) | frame[frame.size() - 1]);
}

// Checks a golden frame: its count, its checksum against checksum(), and that
// the decoder accepts it as exactly one packet with the expected id and payload.
void check_golden(const Bytes& frame) {
  REQUIRE(frame.size() >= 6);
  CHECK(frame[0] == 0xFA);
  CHECK(frame[1] == 0xFB);
  CHECK(frame[2] == frame.size() - 3);
  const std::span<const std::uint8_t> body(frame.data() + 3, frame.size() - 5);
  CHECK(checksum(body) == wire_checksum(frame));
  const Packet p = to_packet(frame);
  CHECK(p.id == frame[3]);
  CHECK(Bytes(p.payload().begin(), p.payload().end()) == Bytes(body.begin() + 1, body.end()));
}

}  // namespace

TEST_CASE("checksum: odd-length body 10 20 30 gives 0x1010") {
  CHECK(checksum(bytes({0x10, 0x20, 0x30})) == 0x1010);
}

TEST_CASE("checksum: word sums, carries dropped, empty body") {
  CHECK(checksum({}) == 0);
  CHECK(checksum(bytes({0x12})) == 0x0012);              // a lone byte goes into the low byte
  CHECK(checksum(bytes({0x12, 0x34})) == 0x1234);        // first byte of a pair is high
  CHECK(checksum(bytes({0xFF, 0xFF, 0x00, 0x02})) == 0x0001);  // 0xFFFF + 2 mod 65536
  CHECK(checksum(bytes({0xFF, 0xFF, 0xFF, 0xFF})) == 0xFFFE);
  CHECK(checksum(bytes({0x00, 0x00, 0xFF})) == 0x00FF);  // XOR, not add, for the odd byte
  CHECK(checksum(bytes({0x00, 0xFF, 0xFF})) == 0x0000);
}

TEST_CASE("checksum: known answers from the protocol doc") {
  CHECK(checksum(bytes({0x0B, 0x3B, 0x2C, 0x01})) == 0x373C);
  CHECK(checksum(bytes({0x15, 0x1B, 0x14, 0x00})) == 0x291B);
  CHECK(checksum(bytes({0x01, 0x3B, 0x01, 0x00})) == 0x023B);
  CHECK(checksum(bytes({0x12, 0x3B, 0x01, 0x00})) == 0x133B);
  CHECK(checksum(bytes({0x20, 0x1B, 0xF6, 0x09})) == 0x1624);
}

TEST_CASE("golden: SYNC0/PULSE, SYNC1, SYNC2") {
  const Bytes sync0 = bytes({0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00});
  const Bytes sync1 = bytes({0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01});
  const Bytes sync2 = bytes({0xFA, 0xFB, 0x03, 0x02, 0x00, 0x02});
  CHECK(to_bytes(encode_command(kSync0)) == sync0);
  CHECK(to_bytes(encode_command(Command::pulse)) == sync0);
  CHECK(to_bytes(encode_command(kSync1)) == sync1);
  CHECK(to_bytes(encode_command(kSync2)) == sync2);
  check_golden(sync0);
  check_golden(sync1);
  check_golden(sync2);
}

TEST_CASE("golden: VEL 300, RVEL -20, OPEN 1, CONFIG 1") {
  const Bytes vel = bytes({0xFA, 0xFB, 0x06, 0x0B, 0x3B, 0x2C, 0x01, 0x37, 0x3C});
  const Bytes rvel = bytes({0xFA, 0xFB, 0x06, 0x15, 0x1B, 0x14, 0x00, 0x29, 0x1B});
  const Bytes open = bytes({0xFA, 0xFB, 0x06, 0x01, 0x3B, 0x01, 0x00, 0x02, 0x3B});
  const Bytes config = bytes({0xFA, 0xFB, 0x06, 0x12, 0x3B, 0x01, 0x00, 0x13, 0x3B});
  CHECK(to_bytes(encode_command(Command::vel, 300)) == vel);
  CHECK(to_bytes(encode_command(Command::rvel, -20)) == rvel);
  CHECK(to_bytes(encode_command(Command::open, 1)) == open);
  CHECK(to_bytes(encode_command(Command::config, 1)) == config);
  for (const Bytes& b : {vel, rvel, open, config}) check_golden(b);
}

TEST_CASE("golden: VEL2 left -10 right +10") {
  const Bytes vel2 = bytes({0xFA, 0xFB, 0x06, 0x20, 0x1B, 0xF6, 0x09, 0x16, 0x24});
  CHECK(to_bytes(encode_vel2(-10, 10)) == vel2);
  check_golden(vel2);
  const Packet packet = to_packet(vel2);  // outlives cmd, whose text points into it
  const DecodedCommand cmd = decode_command(packet);
  CHECK(cmd.value == -2550);  // 0xF60A as a signed 16-bit value
  CHECK(unpack_vel2(cmd.value).left_units == -10);
  CHECK(unpack_vel2(cmd.value).right_units == 10);
}

TEST_CASE("golden: a simulator's SYNC2 reply") {
  Bytes reply = bytes({0xFA, 0xFB, 0x18, 0x02});
  append(reply, std::string_view("AMRISim\0Pioneer\0p3at\0", 21));
  append(reply, bytes({0xE7, 0xBA}));
  REQUIRE(reply.size() == 0x18 + 3);
  check_golden(reply);
  CHECK(to_bytes(encode_identity({"AMRISim", "Pioneer", "p3at"})) == reply);
  const RobotIdentity id = decode_identity(to_packet(reply));
  CHECK(id.name == "AMRISim");
  CHECK(id.robot_class == "Pioneer");
  CHECK(id.subclass == "p3at");
}

TEST_CASE("encode_frame: layout, empty payload, and truncation past kMaxPayload") {
  const Bytes payload = bytes({0x10, 0x20, 0x30});
  const Frame f = encode_frame(0x42, payload);
  CHECK(to_bytes(f) == bytes({0xFA, 0xFB, 0x06, 0x42, 0x10, 0x20, 0x30,
                              // the id is summed too: 0x4210 + 0x2030
                              0x62, 0x40}));
  CHECK(encode_frame(0x07, {}).size == 6);

  Bytes big(kMaxPayload + 10, 0x5A);
  const Frame max = encode_frame(0x99, big);
  CHECK(max.size == kMaxFrame);
  CHECK(max.bytes[2] == 255);
  const Packet p = to_packet(max);
  CHECK(p.payload_size == kMaxPayload);
  CHECK(p.payload()[kMaxPayload - 1] == 0x5A);
}

TEST_CASE("little-endian payload helpers") {
  std::uint8_t buf[2] = {};
  put_u16_le(buf, 0x1234);
  CHECK(buf[0] == 0x34);
  CHECK(buf[1] == 0x12);
  CHECK(get_u16_le(buf) == 0x1234);
  put_u16_le(buf, 0xFFFF);
  CHECK(get_u16_le(buf) == 0xFFFF);
}
