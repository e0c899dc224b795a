#include "p3at/protocols/can/frame.hpp"

#include <algorithm>

namespace p3at::can {
namespace {

constexpr char kHexDigits[] = "0123456789ABCDEF";
// Bits 29..31 of an 8-digit id are SocketCAN's EFF/RTR/ERR flags, never part of an id.
constexpr std::uint32_t kErrorFlagBit = 0x20000000;

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

Error bad_text(std::string_view text, const std::string& what) {
  return make_error(Error::Code::invalid_argument, "invalid CAN frame '" + std::string(text) + "': " + what);
}

void append_hex(std::string& out, std::uint32_t value, int digits) {
  for (int shift = (digits - 1) * 4; shift >= 0; shift -= 4) {
    out.push_back(kHexDigits[(value >> static_cast<unsigned>(shift)) & 0xFu]);
  }
}

}  // namespace

bool operator==(const Frame& a, const Frame& b) {
  if (a.id != b.id || a.extended != b.extended || a.remote != b.remote || a.length != b.length) return false;
  const auto pa = a.payload();
  const auto pb = b.payload();
  return std::equal(pa.begin(), pa.end(), pb.begin(), pb.end());
}

Result<Frame> make_frame(std::uint32_t id, std::span<const std::uint8_t> payload, bool extended) {
  const std::uint32_t max_id = extended ? kMaxExtendedId : kMaxStandardId;
  if (id > max_id) {
    std::string text = "CAN id 0x";
    append_hex(text, id, 8);
    return make_error(Error::Code::invalid_argument,
                      text + (extended ? " does not fit 29 bits" : " does not fit 11 bits (use an extended frame)"));
  }
  if (payload.size() > kMaxDataLength) {
    return make_error(Error::Code::invalid_argument,
                      "CAN payload of " + std::to_string(payload.size()) + " bytes (classic CAN carries at most 8)");
  }
  Frame frame;
  frame.id = id;
  frame.extended = extended;
  frame.length = static_cast<std::uint8_t>(payload.size());
  std::copy(payload.begin(), payload.end(), frame.data.begin());
  return frame;
}

std::string format_frame(const Frame& frame) {
  std::string out;
  out.reserve(3 + 8 + 1 + 2 * kMaxDataLength);
  append_hex(out, frame.id, frame.extended ? 8 : 3);
  out.push_back('#');
  if (frame.remote) {
    out.push_back('R');
    if (frame.length != 0) out.push_back(kHexDigits[frame.length & 0xFu]);
    return out;
  }
  for (const std::uint8_t byte : frame.payload()) append_hex(out, byte, 2);
  return out;
}

Result<Frame> parse_frame(std::string_view text) {
  const std::size_t hash = text.find('#');
  if (hash == std::string_view::npos) return bad_text(text, "expected ID#DATA, e.g. 123#DEADBEEF");
  const std::string_view id_text = text.substr(0, hash);
  std::string_view rest = text.substr(hash + 1);
  if (!rest.empty() && rest.front() == '#') return bad_text(text, "CAN FD frames ('##') are not supported");
  if (id_text.size() != 3 && id_text.size() != 8) {
    return bad_text(text, "the id must have 3 (standard) or 8 (extended) hex digits");
  }
  std::uint32_t id = 0;
  for (const char c : id_text) {
    const int v = hex_value(c);
    if (v < 0) return bad_text(text, "'" + std::string(id_text) + "' is not a hex id");
    id = (id << 4) | static_cast<std::uint32_t>(v);
  }
  Frame frame;
  frame.extended = id_text.size() == 8;
  if (frame.extended && (id & kErrorFlagBit) != 0) return bad_text(text, "error frames are not data frames");
  if (id > (frame.extended ? kMaxExtendedId : kMaxStandardId)) {
    return bad_text(text, frame.extended ? "the id does not fit 29 bits" : "a 3-digit id must be at most 7FF");
  }
  frame.id = id;
  if (!rest.empty() && (rest.front() == 'R' || rest.front() == 'r')) {
    frame.remote = true;
    rest.remove_prefix(1);
    if (rest.size() > 1) return bad_text(text, "expected at most one length digit after R");
    if (rest.size() == 1) {
      const int len = hex_value(rest.front());
      if (len < 0 || len > static_cast<int>(kMaxDataLength)) return bad_text(text, "remote length must be 0-8");
      frame.length = static_cast<std::uint8_t>(len);
    }
    return frame;
  }
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < rest.size()) {
    if (rest[i] == '.') {
      ++i;
      continue;
    }
    if (i + 1 >= rest.size()) return bad_text(text, "the data must be whole bytes (two hex digits each)");
    const int hi = hex_value(rest[i]);
    const int lo = hex_value(rest[i + 1]);
    if (hi < 0 || lo < 0) return bad_text(text, "'" + std::string(rest.substr(i, 2)) + "' is not a hex byte");
    if (count == kMaxDataLength) return bad_text(text, "more than 8 data bytes");
    frame.data[count++] = static_cast<std::uint8_t>((hi << 4) | lo);
    i += 2;
  }
  frame.length = static_cast<std::uint8_t>(count);
  return frame;
}

}  // namespace p3at::can
