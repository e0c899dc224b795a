#include "p3at/protocols/arcos/commands.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>

namespace p3at::arcos {

namespace {

constexpr std::size_t kMaxStringArg = 200;

}  // namespace

const char* command_name(std::uint8_t number) {
  switch (number) {
    case 0: return "PULSE";
    case 1: return "OPEN";
    case 2: return "CLOSE";
    case 3: return "POLLING";
    case 4: return "ENABLE";
    case 5: return "SETA";
    case 6: return "SETV";
    case 7: return "SETO";
    case 8: return "MOVE";
    case 9: return "ROTATE";
    case 10: return "SETRV";
    case 11: return "VEL";
    case 12: return "HEAD";
    case 13: return "DHEAD";
    case 15: return "SAY";
    case 18: return "CONFIG";
    case 19: return "ENCODER";
    case 21: return "RVEL";
    case 23: return "SETRA";
    case 28: return "SONAR";
    case 29: return "STOP";
    case 32: return "VEL2";
    case 44: return "BUMPSTALL";
    case 50: return "HOSTBAUD";
    case 55: return "ESTOP";
    case 58: return "GYRO";
    case 62: return "BATTERYINFO";
    case 253: return "RESET";
    default: return "UNKNOWN";
  }
}

Frame encode_command(std::uint8_t number) { return encode_frame(number, {}); }

Frame encode_command(Command command) { return encode_command(static_cast<std::uint8_t>(command)); }

Frame encode_command(Command command, int value) {
  // 64-bit so that |INT_MIN| does not overflow before saturation.
  const auto wide = static_cast<std::int64_t>(value);
  const std::int64_t magnitude = std::min<std::int64_t>(wide < 0 ? -wide : wide, 0xFFFF);
  std::array<std::uint8_t, 3> payload{};
  payload[0] = value < 0 ? kArgNegative : kArgPositive;
  put_u16_le(payload.data() + 1, static_cast<std::uint16_t>(magnitude));
  return encode_frame(static_cast<std::uint8_t>(command), payload);
}

Frame encode_command(Command command, std::string_view text) {
  const std::size_t n = std::min(text.size(), kMaxStringArg);
  std::array<std::uint8_t, kMaxStringArg + 3> payload{};
  payload[0] = kArgString;
  payload[1] = static_cast<std::uint8_t>(n);
  std::copy_n(text.begin(), n, payload.begin() + 2);
  payload[n + 2] = 0;  // ARIA's terminator, not counted in the length
  return encode_frame(static_cast<std::uint8_t>(command), {payload.data(), n + 3});
}

Frame encode_vel2(int left_units, int right_units) {
  const auto left = static_cast<std::uint8_t>(static_cast<std::int8_t>(std::clamp(left_units, -128, 127)));
  const auto right = static_cast<std::uint8_t>(static_cast<std::int8_t>(std::clamp(right_units, -128, 127)));
  const auto packed = static_cast<std::uint16_t>((left << 8) | right);
  return encode_command(Command::vel2, static_cast<int>(static_cast<std::int16_t>(packed)));
}

DecodedCommand decode_command(const Packet& packet) {
  DecodedCommand out;
  out.number = packet.id;
  const auto payload = packet.payload();
  if (payload.empty()) return out;
  switch (payload[0]) {
    case kArgPositive:
    case kArgNegative: {
      if (payload.size() < 3) {
        out.kind = DecodedCommand::ArgKind::malformed;
        return out;
      }
      const int magnitude = get_u16_le(payload.data() + 1);
      out.kind = DecodedCommand::ArgKind::integer;
      out.value = payload[0] == kArgNegative ? -magnitude : magnitude;
      return out;
    }
    case kArgString: {
      if (payload.size() < 2 || payload.size() - 2 < payload[1]) {
        out.kind = DecodedCommand::ArgKind::malformed;
        return out;
      }
      out.kind = DecodedCommand::ArgKind::string;
      out.text = std::string_view(reinterpret_cast<const char*>(packet.payload_bytes.data() + 2), payload[1]);
      return out;
    }
    default:
      out.kind = DecodedCommand::ArgKind::malformed;
      return out;
  }
}

Vel2 unpack_vel2(int value) {
  const auto raw = static_cast<std::uint16_t>(value & 0xFFFF);
  return Vel2{static_cast<std::int8_t>(raw >> 8), static_cast<std::int8_t>(raw & 0xFFu)};
}

}  // namespace p3at::arcos
