#pragma once
/// The CONFIG reply, packet type 0x20 (docs/arcos-protocol.md §6), field for field.

#include <cstdint>
#include <string>

#include "p3at/protocols/arcos/packet.hpp"

namespace p3at::arcos {

struct ConfigPacket {
  std::string robot_class;
  std::string subclass;
  std::string serial_number;
  std::uint8_t spare = 0;
  std::uint16_t top_rot_vel = 0;      ///< deg/s
  std::uint16_t top_trans_vel = 0;    ///< mm/s
  std::uint16_t top_rot_accel = 0;
  std::uint16_t top_trans_accel = 0;
  std::uint16_t max_pwm = 0;
  std::string name;
  std::uint8_t sip_cycle_ms = 0;
  std::uint8_t host_baud = 0;
  std::uint8_t aux_baud = 0;
  std::uint16_t gripper = 0;
  std::uint16_t front_sonar = 0;
  std::uint8_t rear_sonar = 0;
  std::uint16_t low_battery = 0;      ///< 0.1 V
  std::uint16_t revcount = 0;
  std::uint16_t watchdog_ms = 0;
  std::uint8_t flag_byte = 0;
  std::uint16_t stall_pwm = 0;
  std::uint16_t stall_time = 0;
  std::uint16_t joy_trans_vel = 0;
  std::uint16_t joy_rot_vel = 0;
  std::uint16_t rot_vel_max = 0;      ///< current RotVelMax, deg/s: must be non-zero
  std::uint16_t trans_vel_max = 0;    ///< current TransVelMax, mm/s: must be non-zero
  std::uint16_t rot_accel = 0;
  std::uint16_t rot_decel = 0;
  std::uint16_t rot_kp = 0, rot_kv = 0, rot_ki = 0;
  std::uint16_t trans_accel = 0;
  std::uint16_t trans_decel = 0;
  std::uint16_t trans_kp = 0, trans_kv = 0, trans_ki = 0;
  std::uint8_t front_bumpers = 0, rear_bumpers = 0, charger_type = 0, sonar_cycle = 0;
  std::uint8_t auto_baud = 0, gyro_type = 0;
  std::int16_t drift_factor = 0;
  std::uint8_t aux2_baud = 0, aux3_baud = 0;
  std::uint16_t ticks_per_mm = 0;
  std::uint16_t shutdown_voltage = 0;
  std::string firmware_version;

  bool operator==(const ConfigPacket&) const = default;
};

/// Encodes all fields in wire order as packet 0x20. Strings are cut at their
/// first NUL and to 32 characters, so the packet always fits one frame.
Frame encode_config(const ConfigPacket& config);

/// Decodes a 0x20 packet. Like ARIA, a truncated packet is tolerated: fields
/// past the end read as 0 / empty. `fields_read` (optional) gets how many
/// fields were wholly present.
ConfigPacket decode_config(const Packet& packet, int* fields_read = nullptr);

/// What a simulator answers (§6): class "Pioneer", the given subclass and name,
/// serial "SIM", SIP cycle 100 ms, watchdog 2000 ms, current TransVelMax 3000 mm/s
/// and RotVelMax 150 deg/s, translational accel/decel 300 mm/s², rotational
/// accel/decel 100 deg/s²; top velocities/accelerations at least those (top trans
/// vel 3000 mm/s, top rot vel 300 deg/s, p3at.p's MaxRVelocity).
ConfigPacket simulator_config(const std::string& name, const std::string& subclass);

}  // namespace p3at::arcos
