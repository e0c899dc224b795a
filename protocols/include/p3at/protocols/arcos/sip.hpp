#pragma once
/// Server Information Packets (docs/arcos-protocol.md §5), the SYNC2 identity
/// reply, and odometry helpers for the 15-bit wrapping position counters.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/protocols/arcos/packet.hpp"

namespace p3at::arcos {

inline constexpr std::uint8_t kSipStopped = 0x32;
inline constexpr std::uint8_t kSipMoving = 0x33;
inline constexpr std::uint8_t kConfigPacket = 0x20;
inline constexpr std::uint8_t kEncoderPacket = 0x90;
inline constexpr std::uint8_t kCloseReply = 0xFF;

/// One sonar reading: sonar number and range in raw units (× RangeConvFactor → mm).
struct SonarRaw {
  std::uint8_t number = 0;
  std::uint16_t range = 0;
};

/// Optional groups after the sonar block; each is present only if the ones
/// before it are (a sender writes a prefix of these groups, a reader reads as
/// many as the bytes allow).
struct SipIo {
  std::uint8_t grip_state = 0, anport = 0, analog = 0, digin = 0, digout = 0;
  bool operator==(const SipIo&) const = default;
};

/// A standard SIP, field for field, in raw units.
struct Sip {
  bool moving = false;             ///< packet type 0x33 (else 0x32)
  std::uint16_t xpos = 0;          ///< low 15 bits meaningful
  std::uint16_t ypos = 0;
  std::int16_t thpos = 0;          ///< 4096 per turn
  std::int16_t left_vel = 0;       ///< × VelConvFactor → mm/s
  std::int16_t right_vel = 0;
  std::uint8_t battery = 0;        ///< 0.1 V
  std::uint16_t stall_bumpers = 0;
  std::int16_t control = 0;
  std::uint16_t flags = 0;
  std::uint8_t compass = 0;
  std::uint8_t sonar_count = 0;    ///< entries used in `sonar`
  std::array<SonarRaw, 32> sonar{};
  // Optional groups, in wire order:
  std::optional<SipIo> io;
  std::optional<std::uint16_t> battery_x10;
  std::optional<std::uint8_t> charge_state;
  std::optional<std::int16_t> rotvel;        ///< 0.1 deg/s
  std::optional<std::uint16_t> fault_flags;
  std::optional<std::int16_t> latvel;
  std::optional<std::int8_t> temperature;    ///< °C, -127 none
  std::optional<std::uint8_t> state_of_charge;
  std::optional<std::uint32_t> controller_time_us;
  std::optional<std::uint32_t> flags3;

  bool operator==(const Sip&) const;
};

/// FLAGS bits.
inline constexpr std::uint16_t kFlagMotorsEnabled = 1u << 0;
inline constexpr std::uint16_t kFlagEstop = 1u << 5;
/// STALL/BUMPERS bits.
inline constexpr std::uint16_t kLeftStall = 1u << 0;
inline constexpr std::uint16_t kRightStall = 1u << 8;

/// Encodes a SIP with its optional groups up to the first absent one.
Frame encode_sip(const Sip& sip);

/// Decodes a SIP packet (id 0x32 or 0x33). A packet too short for the
/// mandatory fields or its sonar block is an Error; optional groups are read
/// while whole groups remain.
Result<Sip> decode_sip(const Packet& packet);

/// The SYNC2 reply: three zero-terminated strings.
struct RobotIdentity {
  std::string name;
  std::string robot_class;
  std::string subclass;
};
/// Each string is cut at its first NUL and to 80 characters.
Frame encode_identity(const RobotIdentity& identity);
/// Missing terminators are tolerated (the string ends at the payload end).
RobotIdentity decode_identity(const Packet& packet);

/// Signed difference of two 15-bit position counters, undoing wraps: a jump of
/// more than 0x1000 counts as a wrap of ±0x8000.
int wrap_delta_15bit(std::uint16_t previous, std::uint16_t current);

/// Signed difference of two 4096-per-turn headings, in (-2048, 2048].
int wrap_delta_heading(std::int16_t previous, std::int16_t current);

/// Conversion factors of a Pioneer model (ARIA's .p parameters).
struct RobotParams {
  double dist_conv = 1.0;     ///< position units → mm
  double vel_conv = 1.0;      ///< velocity units → mm/s
  double range_conv = 1.0;    ///< sonar units → mm
  double angle_conv = 0.0015339807878856412;  ///< 2π/4096 rad per unit
  /// rad/s per mm/s: rotational velocity = (right − left) / 2 × diff_conv
  /// (0.0034 ↔ an effective track of ~588 mm).
  double diff_conv = 0.0034;
  int vel2_divisor = 20;

  /// The P3-AT's parameters for a SYNC2 subclass (compared case-insensitively,
  /// like ARIA): "p3at" uses the old encoder units (DistConvFactor 0.465),
  /// "p3at-sh" 1.0; other subclasses get 1.0.
  static RobotParams for_subclass(const std::string& subclass);
};

}  // namespace p3at::arcos
