// libFuzzer target: the ARCOS packet decoder fed in input-derived chunks and
// at input-derived times, and every codec applied to every packet it yields.
// A broken invariant aborts, so libFuzzer reports it as a crash.
//
// Input layout: byte 0 seeds the chunking and timing; the rest is the byte stream.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/packet.hpp"
#include "p3at/protocols/arcos/sip.hpp"

namespace {

using namespace p3at::arcos;

[[noreturn]] void invariant_failed(const char* file, int line, const char* what) {
  std::fprintf(stderr, "%s:%d: invariant failed: %s\n", file, line, what);
  std::abort();
}

#define FUZZ_ASSERT(cond) \
  ((cond) ? static_cast<void>(0) : invariant_failed(__FILE__, __LINE__, #cond))

bool same_packet(const Packet& a, const Packet& b) {
  if (a.id != b.id || a.payload_size != b.payload_size) return false;
  const auto pa = a.payload();
  const auto pb = b.payload();
  for (std::size_t i = 0; i < pa.size(); ++i)
    if (pa[i] != pb[i]) return false;
  return true;
}

// A frame through a fresh decoder: it must be exactly one valid packet.
Packet decode_one(const Frame& frame) {
  PacketDecoder decoder;
  Packet out;
  int count = 0;
  decoder.feed(frame.span(), 0, [&](const Packet& p) {
    out = p;
    ++count;
  });
  FUZZ_ASSERT(count == 1);
  FUZZ_ASSERT(decoder.pending() == 0);
  FUZZ_ASSERT(decoder.stats().errors() == 0);
  FUZZ_ASSERT(decoder.stats().discarded_bytes == 0);
  return out;
}

void check_frame_round_trip(const Packet& packet) {
  const Frame frame = encode_frame(packet.id, packet.payload());
  FUZZ_ASSERT(frame.size == std::size_t{packet.payload_size} + 6);
  FUZZ_ASSERT(same_packet(decode_one(frame), packet));
}

void check_sip(const Packet& packet) {
  const auto sip = decode_sip(packet);
  if (!sip.ok()) {
    FUZZ_ASSERT(sip.error().code == p3at::Error::Code::protocol);
    FUZZ_ASSERT(!sip.error().message.empty());
    return;
  }
  FUZZ_ASSERT(packet.id == kSipStopped || packet.id == kSipMoving);
  FUZZ_ASSERT(sip->sonar_count <= sip->sonar.size());
  // Re-encoding what was decoded gives the same SIP back.
  const auto again = decode_sip(decode_one(encode_sip(*sip)));
  FUZZ_ASSERT(again.ok());
  FUZZ_ASSERT(*again == *sip);
}

void check_config(const Packet& packet) {
  int fields = -1;
  const ConfigPacket config = decode_config(packet, &fields);
  FUZZ_ASSERT(fields >= 0 && fields <= 48);
  const auto short_enough = [](const std::string& s) { return s.size() <= 32; };
  if (fields == 48 && short_enough(config.robot_class) && short_enough(config.subclass) &&
      short_enough(config.serial_number) && short_enough(config.name) && short_enough(config.firmware_version)) {
    int fields_again = -1;
    FUZZ_ASSERT(decode_config(decode_one(encode_config(config)), &fields_again) == config);
    FUZZ_ASSERT(fields_again == 48);
  }
}

void check_identity(const Packet& packet) {
  const RobotIdentity id = decode_identity(packet);
  FUZZ_ASSERT(id.name.size() + id.robot_class.size() + id.subclass.size() <= packet.payload_size);
  if (id.name.size() <= 80 && id.robot_class.size() <= 80 && id.subclass.size() <= 80) {
    const RobotIdentity again = decode_identity(decode_one(encode_identity(id)));
    FUZZ_ASSERT(again.name == id.name && again.robot_class == id.robot_class && again.subclass == id.subclass);
  }
}

void check_command(const Packet& packet) {
  const DecodedCommand cmd = decode_command(packet);
  FUZZ_ASSERT(cmd.number == packet.id);
  FUZZ_ASSERT(command_name(cmd.number) != nullptr);
  switch (cmd.kind) {
    case DecodedCommand::ArgKind::integer: {
      FUZZ_ASSERT(cmd.value >= -65535 && cmd.value <= 65535);
      const DecodedCommand again = decode_command(decode_one(encode_command(static_cast<Command>(cmd.number), cmd.value)));
      FUZZ_ASSERT(again.kind == DecodedCommand::ArgKind::integer && again.value == cmd.value);
      const Vel2 v = unpack_vel2(cmd.value);
      FUZZ_ASSERT(v.left_units >= -128 && v.left_units <= 127 && v.right_units >= -128 && v.right_units <= 127);
      const Vel2 w = unpack_vel2(decode_command(decode_one(encode_vel2(v.left_units, v.right_units))).value);
      FUZZ_ASSERT(w.left_units == v.left_units && w.right_units == v.right_units);
      break;
    }
    case DecodedCommand::ArgKind::string: {
      const auto* begin = reinterpret_cast<const char*>(packet.payload_bytes.data());
      FUZZ_ASSERT(cmd.text.data() >= begin + 2);
      FUZZ_ASSERT(cmd.text.data() + cmd.text.size() <= begin + packet.payload_size);
      if (cmd.text.size() <= 200) {
        // `text` points into its packet, so the packet must outlive it.
        const Packet again_packet = decode_one(encode_command(static_cast<Command>(cmd.number), cmd.text));
        const DecodedCommand again = decode_command(again_packet);
        FUZZ_ASSERT(again.kind == DecodedCommand::ArgKind::string && again.text == cmd.text);
      }
      break;
    }
    case DecodedCommand::ArgKind::none:
      FUZZ_ASSERT(packet.payload_size == 0);
      break;
    case DecodedCommand::ArgKind::malformed:
      FUZZ_ASSERT(packet.payload_size > 0);
      break;
  }
}

// Small deterministic generator for chunk sizes and gaps.
struct Lcg {
  std::uint32_t state;
  std::uint32_t next() {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  Lcg rng{static_cast<std::uint32_t>(data[0]) * 2654435761u + static_cast<std::uint32_t>(size)};
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  // A small timeout some gaps exceed; a limit below 255 on some inputs.
  DecoderLimits limits;
  limits.inter_byte_timeout_us = 1000;
  if ((data[0] & 0x80u) != 0) limits.max_count = 200;
  PacketDecoder decoder(limits);

  std::size_t fed = 0;
  std::size_t delivered_bytes = 0;
  std::size_t expired_bytes = 0;
  std::uint64_t delivered = 0;
  std::int64_t now_us = 0;
  std::size_t pos = 0;
  while (pos < stream.size()) {
    const std::uint32_t r = rng.next();
    const std::size_t n = std::min<std::size_t>(1 + r % 97, stream.size() - pos);
    // Mostly within the timeout, sometimes beyond it.
    now_us += (r >> 12) % 8 == 0 ? 1500 : 10;
    // Expire explicitly first, so the bytes a timeout drops can be counted.
    const std::size_t before = decoder.pending();
    const std::uint64_t timeouts_before = decoder.stats().timeouts;
    decoder.expire(now_us);
    if (decoder.stats().timeouts != timeouts_before) {
      FUZZ_ASSERT(decoder.stats().timeouts == timeouts_before + 1);
      FUZZ_ASSERT(decoder.pending() == 0);
      expired_bytes += before;
    } else {
      FUZZ_ASSERT(decoder.pending() == before);
    }
    decoder.feed(stream.subspan(pos, n), now_us, [&](const Packet& packet) {
      ++delivered;
      delivered_bytes += std::size_t{packet.payload_size} + 6;
      FUZZ_ASSERT(packet.payload_size + 3u <= limits.max_count);
      check_frame_round_trip(packet);
      check_sip(packet);
      check_config(packet);
      check_identity(packet);
      check_command(packet);
    });
    fed += n;
    pos += n;

    const DecoderStats& s = decoder.stats();
    FUZZ_ASSERT(s.packets == delivered);
    FUZZ_ASSERT(decoder.pending() < kMaxFrame);
    // Every byte is in a packet, skipped, the 0xFA of a rejected candidate,
    // dropped by a timeout, or still pending.
    FUZZ_ASSERT(fed == delivered_bytes + s.discarded_bytes + s.bad_header + s.bad_count + s.bad_checksum +
                           expired_bytes + decoder.pending());
    FUZZ_ASSERT(s.errors() == s.bad_header + s.bad_count + s.bad_checksum + s.timeouts);
  }
  return 0;
}
