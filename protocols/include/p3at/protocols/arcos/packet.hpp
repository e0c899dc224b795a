#pragma once
/// ARCOS framing (docs/arcos-protocol.md §1): 0xFA 0xFB, count, id, payload,
/// checksum high byte first. Pure functions, no I/O, no heap.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace p3at::arcos {

inline constexpr std::uint8_t kHeader0 = 0xFA;
inline constexpr std::uint8_t kHeader1 = 0xFB;
/// The count byte covers id + payload + 2 checksum bytes, so the largest payload is 255 - 3.
inline constexpr std::size_t kMaxPayload = 252;
/// Header (2) + count (1) + the largest count (255).
inline constexpr std::size_t kMaxFrame = 258;

/// ARCOS checksum over the id byte and payload: 16-bit big-endian word sum,
/// a trailing odd byte XORed into the low byte.
std::uint16_t checksum(std::span<const std::uint8_t> id_and_payload);

/// One packet: the id (packet type robot→client, command number client→robot)
/// and its payload, without framing or checksum. Fixed capacity, no heap.
struct Packet {
  std::uint8_t id = 0;
  std::uint8_t payload_size = 0;
  std::array<std::uint8_t, kMaxPayload> payload_bytes{};

  std::span<const std::uint8_t> payload() const { return {payload_bytes.data(), payload_size}; }
};

/// Framed bytes ready for the wire.
struct Frame {
  std::array<std::uint8_t, kMaxFrame> bytes{};
  std::size_t size = 0;

  std::span<const std::uint8_t> span() const { return {bytes.data(), size}; }
};

/// Frames `id` + `payload`. A payload longer than kMaxPayload is truncated to
/// kMaxPayload (callers build payloads with the encoders below, which never exceed it).
Frame encode_frame(std::uint8_t id, std::span<const std::uint8_t> payload);

/// Little-endian helpers for payload integers.
inline void put_u16_le(std::uint8_t* out, std::uint16_t v) {
  out[0] = static_cast<std::uint8_t>(v & 0xFFu);
  out[1] = static_cast<std::uint8_t>(v >> 8);
}
inline std::uint16_t get_u16_le(const std::uint8_t* in) {
  return static_cast<std::uint16_t>(in[0] | (in[1] << 8));
}

}  // namespace p3at::arcos
