#pragma once
// Private to the ARCOS codecs: bounded little-endian payload writer and reader.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "p3at/protocols/arcos/packet.hpp"

namespace p3at::arcos::detail {

/// Appends little-endian fields to a payload of at most kMaxPayload bytes;
/// writes past the end are dropped (callers size their payloads to fit).
class PayloadWriter {
 public:
  void u8(std::uint8_t v) {
    if (size_ < bytes_.size()) bytes_[size_++] = v;
  }
  void s8(std::int8_t v) { u8(static_cast<std::uint8_t>(v)); }
  void u16(std::uint16_t v) {
    u8(static_cast<std::uint8_t>(v & 0xFFu));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  void s16(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void u32(std::uint32_t v) {
    u16(static_cast<std::uint16_t>(v & 0xFFFFu));
    u16(static_cast<std::uint16_t>(v >> 16));
  }
  /// Characters up to the first NUL or `max_chars`, then a terminating zero.
  void cstring(std::string_view text, std::size_t max_chars) {
    const std::size_t n = std::min({text.find('\0'), text.size(), max_chars});
    for (std::size_t i = 0; i < n; ++i) u8(static_cast<std::uint8_t>(text[i]));
    u8(0);
  }
  std::span<const std::uint8_t> bytes() const { return {bytes_.data(), size_}; }

 private:
  std::array<std::uint8_t, kMaxPayload> bytes_{};
  std::size_t size_ = 0;
};

/// Reads little-endian fields; each read reports whether the field was whole.
/// A short read leaves the output unchanged and consumes nothing.
class PayloadReader {
 public:
  explicit PayloadReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::size_t remaining() const { return bytes_.size() - pos_; }

  bool u8(std::uint8_t& out) {
    if (remaining() < 1) return false;
    out = bytes_[pos_++];
    return true;
  }
  bool s8(std::int8_t& out) {
    std::uint8_t raw = 0;
    if (!u8(raw)) return false;
    out = static_cast<std::int8_t>(raw);
    return true;
  }
  bool u16(std::uint16_t& out) {
    if (remaining() < 2) return false;
    out = get_u16_le(bytes_.data() + pos_);
    pos_ += 2;
    return true;
  }
  bool s16(std::int16_t& out) {
    std::uint16_t raw = 0;
    if (!u16(raw)) return false;
    out = static_cast<std::int16_t>(raw);
    return true;
  }
  bool u32(std::uint32_t& out) {
    if (remaining() < 4) return false;
    const std::uint32_t low = get_u16_le(bytes_.data() + pos_);
    const std::uint32_t high = get_u16_le(bytes_.data() + pos_ + 2);
    out = low | (high << 16);
    pos_ += 4;
    return true;
  }
  /// A zero-terminated string. Without a terminator the string runs to the end
  /// of the payload: `out` gets it, but the read reports false (not whole).
  bool cstring(std::string& out) {
    const auto rest = bytes_.subspan(pos_);
    const auto* begin = rest.data();
    const auto* end = begin + rest.size();
    const auto* zero = std::find(begin, end, std::uint8_t{0});
    out.assign(begin, zero);
    if (zero == end) {
      pos_ = bytes_.size();
      return false;
    }
    pos_ += static_cast<std::size_t>(zero - begin) + 1;
    return true;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

}  // namespace p3at::arcos::detail
