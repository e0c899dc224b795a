#pragma once
/// Incremental ARCOS packet decoder: feed it any chunking of bytes; it hunts
/// for 0xFA 0xFB, resynchronises after garbage, and counts every kind of bad input.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "p3at/protocols/arcos/packet.hpp"

namespace p3at::arcos {

/// Counters of everything the decoder saw. Never reset by the decoder.
struct DecoderStats {
  std::uint64_t packets = 0;          ///< valid packets delivered
  std::uint64_t bad_header = 0;       ///< 0xFA not followed by 0xFB
  std::uint64_t bad_checksum = 0;     ///< complete packet, wrong checksum: dropped
  std::uint64_t bad_count = 0;        ///< count byte over the limit or under 3: dropped
  std::uint64_t timeouts = 0;         ///< a packet's bytes stopped arriving mid-way: dropped
  std::uint64_t discarded_bytes = 0;  ///< bytes skipped while hunting for a header

  std::uint64_t errors() const { return bad_header + bad_checksum + bad_count + timeouts; }
};

struct DecoderLimits {
  /// Largest acceptable count byte. The protocol says about 200; ARIA's buffer takes 255.
  std::uint8_t max_count = 255;
  /// A packet whose next byte does not arrive within this is abandoned (ARIA: ~100 ms).
  std::int64_t inter_byte_timeout_us = 100'000;
};

class PacketDecoder {
 public:
  explicit PacketDecoder(DecoderLimits limits = {}) : limits_(limits) {}

  /// Feeds a chunk of bytes that arrived at `now_us` and calls `sink(const Packet&)`
  /// for every complete, valid packet, in order. After a bad header, count or
  /// checksum it rescans the dropped bytes, so a real packet hidden behind
  /// garbage is still found.
  template <class Sink>
  void feed(std::span<const std::uint8_t> bytes, std::int64_t now_us, Sink&& sink) {
    expire(now_us);
    while (!bytes.empty()) {
      const std::size_t taken = accept(bytes, now_us);
      bytes = bytes.subspan(taken);
      while (const Packet* packet = next_packet()) sink(*packet);
    }
  }

  /// Abandons a partial packet that has waited longer than the inter-byte
  /// timeout. Call it when a read times out, so a stalled peer is noticed.
  void expire(std::int64_t now_us);

  const DecoderStats& stats() const { return stats_; }

  /// Bytes buffered but not yet part of a delivered packet.
  std::size_t pending() const { return size_; }

 private:
  std::size_t accept(std::span<const std::uint8_t> bytes, std::int64_t now_us);
  const Packet* next_packet();
  void drop_front(std::size_t n);

  DecoderLimits limits_;
  DecoderStats stats_{};
  // Room for one maximal frame plus the next chunk's start; a full frame
  // always fits, so accept() always makes progress.
  std::array<std::uint8_t, 2 * kMaxFrame> buffer_{};
  std::size_t size_ = 0;
  std::int64_t last_byte_us_ = 0;
  Packet packet_{};
};

}  // namespace p3at::arcos
