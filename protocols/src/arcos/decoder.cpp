#include "p3at/protocols/arcos/decoder.hpp"

#include <algorithm>
#include <cstring>

namespace p3at::arcos {

void PacketDecoder::expire(std::int64_t now_us) {
  if (size_ == 0 || now_us <= last_byte_us_) return;
  // Unsigned difference: arbitrary timestamps must not overflow.
  const std::uint64_t gap_us = static_cast<std::uint64_t>(now_us) - static_cast<std::uint64_t>(last_byte_us_);
  if (limits_.inter_byte_timeout_us >= 0 && gap_us > static_cast<std::uint64_t>(limits_.inter_byte_timeout_us)) {
    ++stats_.timeouts;
    size_ = 0;
  }
}

std::size_t PacketDecoder::accept(std::span<const std::uint8_t> bytes, std::int64_t now_us) {
  const std::size_t room = buffer_.size() - size_;
  const std::size_t n = std::min(room, bytes.size());
  std::copy_n(bytes.begin(), n, buffer_.begin() + static_cast<std::ptrdiff_t>(size_));
  size_ += n;
  if (n > 0) last_byte_us_ = now_us;
  return n;
}

void PacketDecoder::drop_front(std::size_t n) {
  n = std::min(n, size_);
  std::memmove(buffer_.data(), buffer_.data() + n, size_ - n);
  size_ -= n;
}

const Packet* PacketDecoder::next_packet() {
  for (;;) {
    if (size_ == 0) return nullptr;
    if (buffer_[0] != kHeader0) {
      const auto* begin = buffer_.data();
      const auto* found = std::find(begin, begin + size_, kHeader0);
      const auto skipped = static_cast<std::size_t>(found - begin);
      stats_.discarded_bytes += skipped;
      drop_front(skipped);
      continue;
    }
    if (size_ < 2) return nullptr;
    if (buffer_[1] != kHeader1) {
      // Drop only the 0xFA: the byte after it may itself start a packet.
      ++stats_.bad_header;
      drop_front(1);
      continue;
    }
    if (size_ < 3) return nullptr;
    const std::uint8_t count = buffer_[2];
    if (count < 3 || count > limits_.max_count) {
      ++stats_.bad_count;
      drop_front(1);
      continue;
    }
    const std::size_t frame_size = std::size_t{count} + 3;
    if (size_ < frame_size) return nullptr;
    const std::span<const std::uint8_t> body{buffer_.data() + 3, std::size_t{count} - 2};
    const auto wire_sum = static_cast<std::uint16_t>((buffer_[frame_size - 2] << 8) | buffer_[frame_size - 1]);
    if (checksum(body) != wire_sum) {
      // Rescan from the byte after the 0xFA: a real packet may hide inside.
      ++stats_.bad_checksum;
      drop_front(1);
      continue;
    }
    packet_.id = body[0];
    packet_.payload_size = static_cast<std::uint8_t>(count - 3);
    std::copy(body.begin() + 1, body.end(), packet_.payload_bytes.begin());
    drop_front(frame_size);
    ++stats_.packets;
    return &packet_;
  }
}

}  // namespace p3at::arcos
