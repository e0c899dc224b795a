#pragma once
/// Payloads of our two accessory nodes' TPDO1 (docs/can-bus.md has the tables):
/// the yaw-rate gyro (100 Hz) and the safety node (e-stop and bumpers, 20 Hz).
/// Pure encode / decode, no I/O.

#include <cstdint>

#include "p3at/common/result.hpp"
#include "p3at/protocols/can/canopen.hpp"
#include "p3at/protocols/can/frame.hpp"

namespace p3at::can {

/// Default node ids on a robot's bus (each is configurable).
inline constexpr std::uint8_t kDefaultGyroNodeId = 0x10;
inline constexpr std::uint8_t kDefaultSafetyNodeId = 0x11;

/// Default producer periods.
inline constexpr std::int64_t kGyroPdoPeriodUs = 10'000;       ///< 100 Hz
inline constexpr std::int64_t kSafetyPdoPeriodUs = 50'000;     ///< 20 Hz
inline constexpr std::int64_t kHeartbeatPeriodUs = 100'000;    ///< both nodes

// ---- gyro TPDO1: yaw rate, temperature, counter, status ----

inline constexpr std::uint8_t kGyroPdoLength = 8;
inline constexpr double kGyroRateLsbRadps = 1e-6;    ///< yaw rate: s32, 1 µrad/s per bit
inline constexpr double kGyroTempLsbC = 0.01;        ///< temperature: s16, 0.01 °C per bit
inline constexpr std::int16_t kGyroTempUnavailable = INT16_MIN;

/// Status byte bits.
inline constexpr std::uint8_t kGyroStatusFault = 0x01;      ///< sensor self-test failed: do not use the rate
inline constexpr std::uint8_t kGyroStatusSaturated = 0x02;  ///< the rate was clipped to the sensor's range

struct GyroSample {
  double yaw_rate_radps = 0.0;  ///< counter-clockwise seen from above is positive (like hal::Pose2)
  bool has_temperature = true;
  double temperature_c = 0.0;
  std::uint8_t counter = 0;     ///< +1 per sample, wraps at 256
  bool fault = false;
  bool saturated = false;
};

/// Encodes a sample; the rate is rounded to 1 µrad/s and clipped to the s32 range
/// (setting `saturated`), the temperature rounded to 0.01 °C and clipped to ±327 °C.
Frame encode_gyro_pdo(std::uint8_t node_id, const GyroSample& sample);
/// Errors: not a TPDO1 COB-ID, length other than 8. Reserved status bits are ignored.
Result<GyroSample> decode_gyro_pdo(const Frame& frame);

// ---- safety node TPDO1: flags, bumpers, counter, check byte ----

inline constexpr std::uint8_t kSafetyPdoLength = 4;
inline constexpr std::uint8_t kSafetyFlagEstop = 0x01;  ///< e-stop button pressed (or its circuit open)
inline constexpr std::uint8_t kSafetyFlagFault = 0x02;  ///< the node's self-test failed
inline constexpr std::uint8_t kSafetyFlagsKnown = kSafetyFlagEstop | kSafetyFlagFault;

struct SafetyState {
  bool estop_pressed = false;
  bool fault = false;
  std::uint8_t bumpers = 0;  ///< bits 0-3 front segments left→right, bits 4-7 rear; 1 = pressed
  std::uint8_t counter = 0;  ///< +1 per message, wraps at 256

  /// Nothing asks the robot to stop.
  bool clear() const { return !estop_pressed && !fault && bumpers == 0; }
};

/// The check byte: 0xFF XOR flags XOR bumpers XOR counter (an all-zero frame fails it).
std::uint8_t safety_check_byte(std::uint8_t flags, std::uint8_t bumpers, std::uint8_t counter);

Frame encode_safety_pdo(std::uint8_t node_id, const SafetyState& state);
/// Errors: not a TPDO1 COB-ID, length other than 4, a wrong check byte, or unknown
/// flag bits set (a safety message we do not fully understand is not trusted).
Result<SafetyState> decode_safety_pdo(const Frame& frame);

}  // namespace p3at::can
