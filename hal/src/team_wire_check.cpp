#include "team_wire_check.hpp"

#include <cstring>

#include "p3at/hal/team_wire.hpp"

namespace p3at::hal::wire_check {

namespace {

// Walks an LCM encoding (big-endian integers, strings as int32 length
// including the NUL, then the bytes and the NUL). Any failure sticks.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  bool ok() const { return ok_; }
  bool at_end() const { return ok_ && pos_ == bytes_.size(); }

  std::uint64_t u64() { return big_endian(8); }
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  std::int16_t i16() { return static_cast<std::int16_t>(static_cast<std::uint16_t>(big_endian(2))); }
  void skip_doubles(std::size_t count) { take(8 * count); }

  void non_negative_i64() {
    if (i64() < 0) ok_ = false;
  }

  void boolean() {
    const std::uint64_t v = big_endian(1);
    if (v > 1) ok_ = false;
  }

  void string(std::size_t max_bytes) {
    const auto length = static_cast<std::int32_t>(static_cast<std::uint32_t>(big_endian(4)));
    if (!ok_) return;
    // The length counts the terminating NUL, so an empty string has length 1.
    if (length < 1 || static_cast<std::size_t>(length) - 1 > max_bytes) {
      ok_ = false;
      return;
    }
    const std::uint8_t* text = take(static_cast<std::size_t>(length));
    if (text == nullptr) return;
    const std::size_t size = static_cast<std::size_t>(length) - 1;
    if (text[size] != 0 || std::memchr(text, 0, size) != nullptr) ok_ = false;
  }

  // An int16 count in [0, max] followed by `count` items read by `item`.
  template <class Item>
  void array(std::size_t max, Item item) {
    const std::int16_t count = i16();
    if (!ok_) return;
    if (count < 0 || static_cast<std::size_t>(count) > max) {
      ok_ = false;
      return;
    }
    for (std::int16_t i = 0; i < count && ok_; ++i) item();
  }

  // tag_len then tag: 0 (no tag) or any length a sender could have meant as a
  // tag is a layout question only; whether it verifies is decided later.
  void tag() {
    const std::int16_t length = i16();
    if (!ok_) return;
    if (length < 0 || static_cast<std::size_t>(length) > 4 * kTeamTagBytes) {
      ok_ = false;
      return;
    }
    take(static_cast<std::size_t>(length));
  }

  void fingerprint(std::int64_t expected) {
    if (i64() != expected) ok_ = false;
  }

 private:
  const std::uint8_t* take(std::size_t count) {
    if (!ok_ || bytes_.size() - pos_ < count) {
      ok_ = false;
      return nullptr;
    }
    const std::uint8_t* p = bytes_.data() + pos_;
    pos_ += count;
    return p;
  }

  std::uint64_t big_endian(std::size_t count) {
    const std::uint8_t* p = take(count);
    if (p == nullptr) return 0;
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < count; ++i) v = (v << 8) | p[i];
    return v;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace

bool notification_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint) {
  Reader r(bytes);
  r.fingerprint(fingerprint);
  r.i64();  // utime
  r.string(kMaxTeamNameBytes);     // mission_id
  r.string(kSessionHexDigits);     // session (its digits are checked after decoding)
  r.string(kMaxTeamNameBytes);     // sender
  r.non_negative_i64();            // seq
  r.string(kMaxTeamMessageBytes);  // message
  r.boolean();                     // is_ack
  r.string(kMaxTeamNameBytes);     // ack_sender
  r.non_negative_i64();            // ack_seq
  r.array(kMaxTeamRecipients, [&r] { r.string(kMaxTeamNameBytes); });  // recipients
  r.tag();
  return r.at_end();
}

bool status_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint) {
  Reader r(bytes);
  r.fingerprint(fingerprint);
  r.i64();                       // utime
  r.string(kMaxTeamNameBytes);   // mission_id
  r.string(kSessionHexDigits);   // session
  r.string(kMaxTeamNameBytes);   // robot
  r.non_negative_i64();          // seq
  r.string(kMaxTeamTextBytes);   // phase
  r.string(kMaxTeamTextBytes);   // state
  r.string(kMaxTeamTextBytes);   // reason
  r.skip_doubles(1);             // p_success (finiteness checked after decoding)
  r.tag();
  return r.at_end();
}

bool telemetry_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint) {
  Reader r(bytes);
  r.fingerprint(fingerprint);
  r.i64();                       // utime
  r.string(kMaxTeamNameBytes);   // mission_id
  r.string(kSessionHexDigits);   // session
  r.string(kMaxTeamNameBytes);   // robot
  r.non_negative_i64();          // seq
  r.string(kMaxTeamTextBytes);   // state
  r.skip_doubles(3);             // pose2d_t: x_m, y_m, theta_rad
  r.skip_doubles(2);             // trans_vel_mps, rot_vel_radps
  r.non_negative_i64();          // cycle_stats_t: cycles
  r.non_negative_i64();          //   overruns
  r.non_negative_i64();          //   missed_updates
  r.skip_doubles(2);             //   p50_us, p99_us
  r.tag();
  return r.at_end();
}

bool verdict_layout_ok(std::span<const std::uint8_t> bytes, std::int64_t fingerprint) {
  Reader r(bytes);
  r.fingerprint(fingerprint);
  r.i64();                           // utime
  r.string(kMaxTeamNameBytes);       // mission_id
  r.string(kMaxTeamNameBytes);       // robot
  r.non_negative_i64();              // seq
  r.string(kMissionHashHexDigits);   // mission_hash (its digits are checked after decoding)
  r.string(kMaxTeamNameBytes);       // decision (its value is checked after decoding)
  r.skip_doubles(6);                 // p_time, p_radius, p_joint, threshold, tmax_s, rmax_m
  r.string(kMaxTeamTextBytes);       // detail
  r.string(kGateNonceHexDigits);     // nonce (digits checked after decoding)
  r.string(kSessionHexDigits);       // session
  // num_heard, then as many robot names and as many nonces (lcm-gen's layout
  // for two arrays sized by one count)
  const std::int16_t heard = r.i16();
  if (heard < 0 || static_cast<std::size_t>(heard) > kMaxTeamRecipients) return false;
  for (std::int16_t i = 0; i < heard; ++i) r.string(kMaxTeamNameBytes);
  for (std::int16_t i = 0; i < heard; ++i) r.string(kGateNonceHexDigits);
  r.tag();
  return r.at_end();
}

}  // namespace p3at::hal::wire_check
