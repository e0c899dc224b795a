#include "p3at/protocols/arcos/packet.hpp"

#include <algorithm>

namespace p3at::arcos {

std::uint16_t checksum(std::span<const std::uint8_t> id_and_payload) {
  std::uint32_t sum = 0;
  std::size_t i = 0;
  for (; i + 1 < id_and_payload.size(); i += 2) {
    sum += static_cast<std::uint32_t>(id_and_payload[i] << 8) | id_and_payload[i + 1];
    sum &= 0xFFFFu;
  }
  if (i < id_and_payload.size()) sum ^= id_and_payload[i];
  return static_cast<std::uint16_t>(sum);
}

Frame encode_frame(std::uint8_t id, std::span<const std::uint8_t> payload) {
  const std::size_t n = std::min(payload.size(), kMaxPayload);
  Frame frame;
  frame.bytes[0] = kHeader0;
  frame.bytes[1] = kHeader1;
  frame.bytes[2] = static_cast<std::uint8_t>(n + 3);
  frame.bytes[3] = id;
  std::copy_n(payload.begin(), n, frame.bytes.begin() + 4);
  const std::uint16_t sum = checksum({frame.bytes.data() + 3, n + 1});
  frame.bytes[4 + n] = static_cast<std::uint8_t>(sum >> 8);
  frame.bytes[5 + n] = static_cast<std::uint8_t>(sum & 0xFFu);
  frame.size = n + 6;
  return frame;
}

}  // namespace p3at::arcos
