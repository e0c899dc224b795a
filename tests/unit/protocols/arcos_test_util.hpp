#pragma once
// Shared helpers of the ARCOS codec tests.

#include <doctest/doctest.h>

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string_view>
#include <vector>

#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/packet.hpp"

namespace p3at::arcos::test {

using Bytes = std::vector<std::uint8_t>;

/// Bytes from a list of ints written like the doc's hex vectors.
inline Bytes bytes(std::initializer_list<int> values) {
  Bytes out;
  for (int v : values) out.push_back(static_cast<std::uint8_t>(v));
  return out;
}

/// Appends the characters of `text` (embedded NULs included).
inline void append(Bytes& out, std::string_view text) {
  for (char c : text) out.push_back(static_cast<std::uint8_t>(c));
}

inline void append(Bytes& out, std::span<const std::uint8_t> more) { out.insert(out.end(), more.begin(), more.end()); }

inline Bytes to_bytes(const Frame& frame) { return Bytes(frame.span().begin(), frame.span().end()); }

/// Runs a frame through a fresh decoder and returns the one packet it must yield.
inline Packet to_packet(std::span<const std::uint8_t> frame) {
  PacketDecoder decoder;
  std::vector<Packet> packets;
  decoder.feed(frame, 0, [&](const Packet& p) { packets.push_back(p); });
  REQUIRE(packets.size() == 1);
  CHECK(decoder.pending() == 0);
  return packets.front();
}
inline Packet to_packet(const Frame& frame) { return to_packet(frame.span()); }

/// A packet built directly (no framing), for decoder-independent codec tests.
inline Packet make_packet(std::uint8_t id, std::span<const std::uint8_t> payload) {
  Packet p;
  p.id = id;
  REQUIRE(payload.size() <= kMaxPayload);
  p.payload_size = static_cast<std::uint8_t>(payload.size());
  for (std::size_t i = 0; i < payload.size(); ++i) p.payload_bytes[i] = payload[i];
  return p;
}

}  // namespace p3at::arcos::test
