// The incremental packet decoder: chunking, resynchronisation, counters, timeouts.

#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "arcos_test_util.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/decoder.hpp"

using namespace p3at::arcos;
using namespace p3at::arcos::test;

namespace {

struct Received {
  std::uint8_t id;
  Bytes payload;
  bool operator==(const Received&) const = default;
};

class Harness {
 public:
  explicit Harness(DecoderLimits limits = {}) : decoder(limits) {}

  void feed(std::span<const std::uint8_t> b, std::int64_t now_us = 0) {
    fed += b.size();
    decoder.feed(b, now_us, [&](const Packet& p) {
      packets.push_back({p.id, Bytes(p.payload().begin(), p.payload().end())});
      delivered_bytes += std::size_t{p.payload_size} + 6;
    });
  }
  void feed_bytewise(std::span<const std::uint8_t> b, std::int64_t now_us = 0) {
    for (std::size_t i = 0; i < b.size(); ++i) feed(b.subspan(i, 1), now_us);
  }

  // Every byte fed is in a delivered packet, was skipped while hunting, is the
  // 0xFA of a rejected candidate (one per bad header/count/checksum), or is pending.
  void check_bytes_accounted() const {
    const DecoderStats& s = decoder.stats();
    CHECK(s.timeouts == 0);
    CHECK(fed == delivered_bytes + s.discarded_bytes + s.bad_header + s.bad_count + s.bad_checksum +
                     decoder.pending());
  }

  PacketDecoder decoder;
  std::vector<Received> packets;
  std::size_t fed = 0;
  std::size_t delivered_bytes = 0;
};

Received received(const Frame& f) {
  const Packet p = to_packet(f);
  return {p.id, Bytes(p.payload().begin(), p.payload().end())};
}

// A varied stream of real frames.
std::vector<Frame> sample_frames() {
  std::vector<Frame> frames;
  frames.push_back(encode_command(kSync0));
  frames.push_back(encode_command(Command::vel, 300));
  frames.push_back(encode_command(Command::rvel, -20));
  frames.push_back(encode_command(Command::say, std::string_view("hello\xFA\xFB")));
  frames.push_back(encode_vel2(-10, 10));
  Bytes payload(kMaxPayload);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(0xF0 + i % 16);
  frames.push_back(encode_frame(0x32, payload));  // count 255, full of 0xFA/0xFB
  frames.push_back(encode_command(Command::stop));
  return frames;
}

Bytes concat(const std::vector<Frame>& frames) {
  Bytes out;
  for (const Frame& f : frames) append(out, f.span());
  return out;
}

std::vector<Received> expected(const std::vector<Frame>& frames) {
  std::vector<Received> out;
  for (const Frame& f : frames) out.push_back(received(f));
  return out;
}

}  // namespace

TEST_CASE("decoder: one packet in one chunk") {
  Harness h;
  h.feed(encode_command(Command::vel, 300).span());
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0].id == 11);
  CHECK(h.packets[0].payload == bytes({0x3B, 0x2C, 0x01}));
  CHECK(h.decoder.stats().packets == 1);
  CHECK(h.decoder.stats().errors() == 0);
  CHECK(h.decoder.pending() == 0);
}

TEST_CASE("decoder: concatenated packets in one chunk") {
  const auto frames = sample_frames();
  Harness h;
  h.feed(concat(frames));
  CHECK(h.packets == expected(frames));
  CHECK(h.decoder.stats().packets == frames.size());
  CHECK(h.decoder.stats().errors() == 0);
  CHECK(h.decoder.stats().discarded_bytes == 0);
  h.check_bytes_accounted();
}

TEST_CASE("decoder: byte by byte") {
  const auto frames = sample_frames();
  Harness h;
  h.feed_bytewise(concat(frames));
  CHECK(h.packets == expected(frames));
  CHECK(h.decoder.stats().errors() == 0);
  CHECK(h.decoder.pending() == 0);
}

TEST_CASE("decoder: random chunkings give the same packets") {
  const auto frames = sample_frames();
  const Bytes stream = concat(frames);
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 300; ++trial) {
    Harness h;
    std::uniform_int_distribution<std::size_t> chunk(1, trial % 2 == 0 ? 8 : 600);
    std::size_t pos = 0;
    while (pos < stream.size()) {
      const std::size_t n = std::min(chunk(rng), stream.size() - pos);
      h.feed(std::span<const std::uint8_t>(stream).subspan(pos, n));
      pos += n;
    }
    REQUIRE(h.packets == expected(frames));
    REQUIRE(h.decoder.stats().errors() == 0);
    REQUIRE(h.decoder.pending() == 0);
  }
}

TEST_CASE("decoder: truncated input stays pending until completed") {
  const Frame f = encode_command(Command::vel, 300);
  Harness h;
  h.feed(f.span().first(5));
  CHECK(h.packets.empty());
  CHECK(h.decoder.pending() == 5);
  CHECK(h.decoder.stats().errors() == 0);
  h.feed(f.span().subspan(5));
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0] == received(f));
  CHECK(h.decoder.pending() == 0);
}

TEST_CASE("decoder: corrupted checksum is dropped and the next packet survives") {
  Bytes bad = to_bytes(encode_command(Command::vel, 300));
  bad.back() ^= 0x01;
  const Frame good = encode_command(Command::rvel, -20);
  Bytes stream = bad;
  append(stream, good.span());
  for (bool bytewise : {false, true}) {
    Harness h;
    if (bytewise) {
      h.feed_bytewise(stream);
    } else {
      h.feed(stream);
    }
    REQUIRE(h.packets.size() == 1);
    CHECK(h.packets[0] == received(good));
    CHECK(h.decoder.stats().bad_checksum == 1);
    CHECK(h.decoder.stats().packets == 1);
    // The rest of the bad frame (everything after its 0xFA) was rescanned as garbage.
    CHECK(h.decoder.stats().discarded_bytes == bad.size() - 1);
    h.check_bytes_accounted();
  }
}

TEST_CASE("decoder: corrupted payload byte is caught by the checksum") {
  Bytes bad = to_bytes(encode_command(Command::vel, 300));
  bad[5] ^= 0x40;
  Harness h;
  h.feed(bad);
  CHECK(h.packets.empty());
  CHECK(h.decoder.stats().bad_checksum == 1);
}

TEST_CASE("decoder: a real packet hidden inside a corrupted one is found") {
  const Frame inner = encode_command(Command::vel, 300);
  // An outer "packet" whose count covers the inner frame plus two checksum bytes
  // that are wrong: after rejecting it the decoder must rescan and find `inner`.
  Bytes stream = bytes({0xFA, 0xFB, static_cast<int>(1 + inner.size + 2), 0x77});
  append(stream, inner.span());
  append(stream, bytes({0x00, 0x00}));
  REQUIRE(stream.size() == std::size_t{stream[2]} + 3);
  Harness h;
  h.feed(stream);
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0] == received(inner));
  CHECK(h.decoder.stats().bad_checksum == 1);
  h.check_bytes_accounted();
}

TEST_CASE("decoder: garbage before and between packets is skipped and counted") {
  const Frame a = encode_command(Command::vel, 300);
  const Frame b = encode_command(Command::stop);
  Bytes stream = bytes({0x00, 0x11, 0xFB, 0x3B});
  append(stream, a.span());
  append(stream, bytes({0x55, 0x66, 0x77}));
  append(stream, b.span());
  append(stream, bytes({0x01}));
  Harness h;
  h.feed(stream);
  CHECK(h.packets == std::vector<Received>{received(a), received(b)});
  CHECK(h.decoder.stats().discarded_bytes == 8);
  CHECK(h.decoder.stats().errors() == 0);
  CHECK(h.decoder.pending() == 0);
  h.check_bytes_accounted();
}

TEST_CASE("decoder: 0xFA 0xFA 0xFB is one bad header then a packet") {
  const Frame f = encode_command(Command::vel, 300);
  Bytes stream = bytes({0xFA});
  append(stream, f.span());
  for (bool bytewise : {false, true}) {
    Harness h;
    if (bytewise) {
      h.feed_bytewise(stream);
    } else {
      h.feed(stream);
    }
    REQUIRE(h.packets.size() == 1);
    CHECK(h.packets[0] == received(f));
    CHECK(h.decoder.stats().bad_header == 1);
    CHECK(h.decoder.stats().discarded_bytes == 0);
    h.check_bytes_accounted();
  }
}

TEST_CASE("decoder: a packet right after a bad header") {
  const Frame f = encode_command(Command::rvel, -20);
  Bytes stream = bytes({0xFA, 0x00});
  append(stream, f.span());
  Harness h;
  h.feed(stream);
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0] == received(f));
  CHECK(h.decoder.stats().bad_header == 1);
  CHECK(h.decoder.stats().discarded_bytes == 1);  // the 0x00
  h.check_bytes_accounted();
}

TEST_CASE("decoder: undersize count is rejected and the stream rescanned") {
  const Frame f = encode_command(Command::open, 1);
  for (int count : {0, 1, 2}) {
    Bytes stream = bytes({0xFA, 0xFB, count});
    append(stream, f.span());
    Harness h;
    h.feed(stream);
    REQUIRE(h.packets.size() == 1);
    CHECK(h.packets[0] == received(f));
    CHECK(h.decoder.stats().bad_count == 1);
    h.check_bytes_accounted();
  }
}

TEST_CASE("decoder: oversize count is rejected against the limit") {
  const Frame f = encode_command(Command::open, 1);
  DecoderLimits limits;
  limits.max_count = 200;
  Bytes stream = bytes({0xFA, 0xFB, 201});
  append(stream, f.span());
  Harness h(limits);
  h.feed_bytewise(stream);
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0] == received(f));
  CHECK(h.decoder.stats().bad_count == 1);
  h.check_bytes_accounted();

  // Exactly the limit is accepted.
  const Frame at_limit = encode_frame(0x32, Bytes(197, 0x01));
  REQUIRE(at_limit.bytes[2] == 200);
  Harness ok(limits);
  ok.feed(at_limit.span());
  CHECK(ok.packets.size() == 1);
  CHECK(ok.decoder.stats().bad_count == 0);
}

TEST_CASE("decoder: default limits accept the largest frame, count 255") {
  const Frame f = encode_frame(0x33, Bytes(kMaxPayload, 0xFA));
  Harness h;
  h.feed_bytewise(f.span());
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0].payload.size() == kMaxPayload);
}

TEST_CASE("decoder: chunks larger than the internal buffer") {
  std::vector<Frame> frames;
  for (int i = 0; i < 40; ++i) frames.push_back(encode_frame(static_cast<std::uint8_t>(i), Bytes(100, 0xFB)));
  Harness h;
  h.feed(concat(frames));  // ~4 KB in one call
  CHECK(h.packets == expected(frames));
  CHECK(h.decoder.stats().errors() == 0);
}

TEST_CASE("decoder: inter-byte timeout abandons a partial packet") {
  const Frame f = encode_command(Command::vel, 300);
  const Frame next = encode_command(Command::stop);
  Harness h;
  h.feed(f.span().first(4), 1'000'000);
  // The rest arrives 100.001 ms later: the partial is abandoned, its tail is garbage.
  h.feed(f.span().subspan(4), 1'100'001);
  CHECK(h.packets.empty());
  CHECK(h.decoder.stats().timeouts == 1);
  CHECK(h.decoder.stats().discarded_bytes == f.size - 4);
  h.feed(next.span(), 1'100'002);
  REQUIRE(h.packets.size() == 1);
  CHECK(h.packets[0] == received(next));
}

TEST_CASE("decoder: a gap of exactly the timeout is still in time") {
  const Frame f = encode_command(Command::vel, 300);
  Harness h;
  h.feed(f.span().first(3), 0);
  h.feed(f.span().subspan(3, 2), 100'000);
  h.feed(f.span().subspan(5), 200'000);  // measured from the last byte, not the first
  CHECK(h.packets.size() == 1);
  CHECK(h.decoder.stats().timeouts == 0);
}

TEST_CASE("decoder: expire() notices a stalled peer without new bytes") {
  const Frame f = encode_command(Command::vel, 300);
  PacketDecoder d;
  d.feed(f.span().first(6), 50, [](const Packet&) { FAIL("no packet expected"); });
  d.expire(100'050);
  CHECK(d.stats().timeouts == 0);
  CHECK(d.pending() == 6);
  d.expire(100'051);
  CHECK(d.stats().timeouts == 1);
  CHECK(d.pending() == 0);
  d.expire(10'000'000);  // nothing pending: nothing to time out
  CHECK(d.stats().timeouts == 1);
}

TEST_CASE("decoder: custom timeout and a clock that goes backwards") {
  DecoderLimits limits;
  limits.inter_byte_timeout_us = 10;
  PacketDecoder d(limits);
  const Frame f = encode_command(Command::vel, 300);
  d.feed(f.span().first(2), 1000, [](const Packet&) {});
  d.expire(500);  // earlier than the last byte: not a timeout
  CHECK(d.stats().timeouts == 0);
  d.expire(1011);
  CHECK(d.stats().timeouts == 1);
}

TEST_CASE("decoder: an oversize count swallowing a real packet gives up at the timeout") {
  const Frame inner = encode_command(Command::vel, 300);
  Bytes stream = bytes({0xFA, 0xFB, 200});
  append(stream, inner.span());
  Harness h;
  h.feed(stream, 0);
  CHECK(h.packets.empty());  // still waiting for 200 bytes
  h.decoder.expire(200'000);
  CHECK(h.decoder.stats().timeouts == 1);
  CHECK(h.decoder.pending() == 0);
  h.feed(inner.span(), 200'001);
  CHECK(h.packets.size() == 1);
}

TEST_CASE("decoder: random garbage interleaved with frames, random chunks") {
  const auto frames = sample_frames();
  std::mt19937 rng(777);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 100; ++trial) {
    // Garbage without 0xFA cannot start a false packet, so every frame must be found.
    Bytes stream;
    std::size_t garbage = 0;
    for (const Frame& f : frames) {
      const int n = byte(rng) % 12;
      for (int i = 0; i < n; ++i) {
        int g = byte(rng);
        if (g == 0xFA) g = 0xFB;
        stream.push_back(static_cast<std::uint8_t>(g));
        ++garbage;
      }
      append(stream, f.span());
    }
    Harness h;
    std::size_t pos = 0;
    while (pos < stream.size()) {
      const std::size_t n = std::min<std::size_t>(1 + static_cast<std::size_t>(byte(rng)) % 40, stream.size() - pos);
      h.feed(std::span<const std::uint8_t>(stream).subspan(pos, n));
      pos += n;
    }
    REQUIRE(h.packets == expected(frames));
    REQUIRE(h.decoder.stats().discarded_bytes == garbage);
    REQUIRE(h.decoder.stats().errors() == 0);
  }
}

TEST_CASE("decoder: pure noise never crashes and every byte is accounted for") {
  std::mt19937 rng(4242);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 50; ++trial) {
    Bytes noise(2000);
    for (auto& b : noise) {
      // Lots of header bytes, to exercise every rejection path.
      const int r = byte(rng);
      b = static_cast<std::uint8_t>(r < 40 ? 0xFA : r < 80 ? 0xFB : byte(rng));
    }
    Harness h;
    std::size_t pos = 0;
    while (pos < noise.size()) {
      const std::size_t n = std::min<std::size_t>(1 + static_cast<std::size_t>(byte(rng)) % 64, noise.size() - pos);
      h.feed(std::span<const std::uint8_t>(noise).subspan(pos, n));
      pos += n;
    }
    CHECK(h.decoder.pending() < kMaxFrame);
    CHECK(h.decoder.stats().packets == h.packets.size());
    h.check_bytes_accounted();
  }
}
