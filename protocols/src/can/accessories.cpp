#include "p3at/protocols/can/accessories.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace p3at::can {
namespace {

Error pdo_error(const Frame& frame, const char* device, const std::string& detail) {
  return make_error(Error::Code::protocol,
                    std::string(device) + " TPDO1 from node " + std::to_string(frame.id & 0x7Fu) + ": " + detail);
}

Result<std::uint8_t> check_pdo_frame(const Frame& frame, const char* device, std::uint8_t expected_length) {
  const CobId cob = classify(frame);
  if (cob.kind != MessageKind::tpdo1) return pdo_error(frame, device, "not a TPDO1 COB-ID");
  if (frame.length != expected_length) {
    return pdo_error(frame, device,
                     "length " + std::to_string(frame.length) + " (expected " + std::to_string(expected_length) + ")");
  }
  return cob.node_id;
}

// Rounds and clips to the integer type's range; `clipped` says whether it had to.
template <class Int>
Int round_clip(double value, bool& clipped) {
  constexpr auto lo = static_cast<double>(std::numeric_limits<Int>::min());
  constexpr auto hi = static_cast<double>(std::numeric_limits<Int>::max());
  const double r = std::nearbyint(value);
  if (std::isnan(r)) {
    clipped = true;
    return 0;
  }
  if (r < lo) {
    clipped = true;
    return std::numeric_limits<Int>::min();
  }
  if (r > hi) {
    clipped = true;
    return std::numeric_limits<Int>::max();
  }
  return static_cast<Int>(r);
}

}  // namespace

Frame encode_gyro_pdo(std::uint8_t node_id, const GyroSample& sample) {
  Frame frame;
  frame.id = tpdo1_cob_id(node_id & kMaxNodeId);
  frame.length = kGyroPdoLength;
  bool saturated = sample.saturated;
  const auto rate = round_clip<std::int32_t>(sample.yaw_rate_radps / kGyroRateLsbRadps, saturated);
  put_le32(frame.data.data(), static_cast<std::uint32_t>(rate));
  std::int16_t temp = kGyroTempUnavailable;
  if (sample.has_temperature) {
    bool ignored = false;
    temp = round_clip<std::int16_t>(sample.temperature_c / kGyroTempLsbC, ignored);
    if (temp == kGyroTempUnavailable) temp = static_cast<std::int16_t>(kGyroTempUnavailable + 1);
  }
  put_le16(frame.data.data() + 4, static_cast<std::uint16_t>(temp));
  frame.data[6] = sample.counter;
  frame.data[7] = static_cast<std::uint8_t>((sample.fault ? kGyroStatusFault : 0) | (saturated ? kGyroStatusSaturated : 0));
  return frame;
}

Result<GyroSample> decode_gyro_pdo(const Frame& frame) {
  if (auto ok = check_pdo_frame(frame, "gyro", kGyroPdoLength); !ok) return ok.error();
  GyroSample sample;
  const auto rate = static_cast<std::int32_t>(get_le32(frame.data.data()));
  sample.yaw_rate_radps = static_cast<double>(rate) * kGyroRateLsbRadps;
  const auto temp = static_cast<std::int16_t>(get_le16(frame.data.data() + 4));
  sample.has_temperature = temp != kGyroTempUnavailable;
  sample.temperature_c = sample.has_temperature ? static_cast<double>(temp) * kGyroTempLsbC : 0.0;
  sample.counter = frame.data[6];
  sample.fault = (frame.data[7] & kGyroStatusFault) != 0;
  sample.saturated = (frame.data[7] & kGyroStatusSaturated) != 0;
  return sample;
}

std::uint8_t safety_check_byte(std::uint8_t flags, std::uint8_t bumpers, std::uint8_t counter) {
  return static_cast<std::uint8_t>(0xFFu ^ flags ^ bumpers ^ counter);
}

Frame encode_safety_pdo(std::uint8_t node_id, const SafetyState& state) {
  Frame frame;
  frame.id = tpdo1_cob_id(node_id & kMaxNodeId);
  frame.length = kSafetyPdoLength;
  const auto flags =
      static_cast<std::uint8_t>((state.estop_pressed ? kSafetyFlagEstop : 0) | (state.fault ? kSafetyFlagFault : 0));
  frame.data[0] = flags;
  frame.data[1] = state.bumpers;
  frame.data[2] = state.counter;
  frame.data[3] = safety_check_byte(flags, state.bumpers, state.counter);
  return frame;
}

Result<SafetyState> decode_safety_pdo(const Frame& frame) {
  if (auto ok = check_pdo_frame(frame, "safety", kSafetyPdoLength); !ok) return ok.error();
  const std::uint8_t flags = frame.data[0];
  if (frame.data[3] != safety_check_byte(flags, frame.data[1], frame.data[2])) {
    return pdo_error(frame, "safety", "check byte mismatch");
  }
  if ((flags & ~kSafetyFlagsKnown) != 0) {
    return pdo_error(frame, "safety", "unknown flag bits " + std::to_string(flags & ~kSafetyFlagsKnown));
  }
  SafetyState state;
  state.estop_pressed = (flags & kSafetyFlagEstop) != 0;
  state.fault = (flags & kSafetyFlagFault) != 0;
  state.bumpers = frame.data[1];
  state.counter = frame.data[2];
  return state;
}

}  // namespace p3at::can
