#pragma once
/// ARCOS client commands (docs/arcos-protocol.md §2 and §4): encoders for the
/// client side and a decoder for the robot side (our firmware emulator).

#include <cstdint>
#include <optional>
#include <string_view>

#include "p3at/protocols/arcos/packet.hpp"

namespace p3at::arcos {

/// Command numbers. SYNC0/1/2 share numbers 0/1/2 with PULSE/OPEN/CLOSE;
/// which is meant depends on the connection phase.
enum class Command : std::uint8_t {
  pulse = 0,
  open = 1,
  close = 2,
  polling = 3,
  enable = 4,
  seta = 5,
  setv = 6,
  seto = 7,
  move = 8,
  rotate = 9,
  setrv = 10,
  vel = 11,
  head = 12,
  dhead = 13,
  say = 15,
  config = 18,
  encoder = 19,
  rvel = 21,
  setra = 23,
  sonar = 28,
  stop = 29,
  vel2 = 32,
  bumpstall = 44,
  hostbaud = 50,
  estop = 55,
  gyro = 58,
  batteryinfo = 62,
  reset = 253,
};
inline constexpr std::uint8_t kSync0 = 0;
inline constexpr std::uint8_t kSync1 = 1;
inline constexpr std::uint8_t kSync2 = 2;

/// Argument type bytes.
inline constexpr std::uint8_t kArgPositive = 0x3B;
inline constexpr std::uint8_t kArgNegative = 0x1B;
inline constexpr std::uint8_t kArgString = 0x2B;

/// Name of a command for logs ("VEL", "RVEL", …); "UNKNOWN" for other numbers.
const char* command_name(std::uint8_t number);

/// A command with no argument (count 3), e.g. PULSE, STOP, SYNC0.
Frame encode_command(std::uint8_t number);
Frame encode_command(Command command);

/// A command with an integer argument: 0x3B + magnitude (u16 LE) when value >= 0,
/// 0x1B + magnitude when negative. |value| is saturated to 65535.
Frame encode_command(Command command, int value);

/// A command with a string argument: 0x2B, length, characters, and ARIA's
/// trailing zero (not counted in the length). Longer strings are cut to 200 characters.
Frame encode_command(Command command, std::string_view text);

/// VEL2: left and right wheel velocities in units of 20 mm/s (each clamped to
/// -128..127), packed left-high / right-low into one 16-bit value, then sign-split.
Frame encode_vel2(int left_units, int right_units);

/// A command as the robot sees it.
struct DecodedCommand {
  enum class ArgKind { none, integer, string, malformed };
  std::uint8_t number = 0;
  ArgKind kind = ArgKind::none;
  int value = 0;                  ///< integer argument (sign applied)
  std::string_view text;          ///< string argument; points into the packet, so the packet
                                  ///< must outlive this result when text is used
};

/// Decodes a command packet's argument. Extra bytes after an argument are
/// ignored (ARIA sends some with arguments the robot does not need).
DecodedCommand decode_command(const Packet& packet);

/// Splits a VEL2 argument back into (left, right) in 20 mm/s units.
struct Vel2 {
  int left_units = 0;
  int right_units = 0;
};
Vel2 unpack_vel2(int value);

}  // namespace p3at::arcos
