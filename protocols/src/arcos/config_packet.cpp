#include "p3at/protocols/arcos/config_packet.hpp"

#include <string_view>

#include "byte_io.hpp"
#include "p3at/protocols/arcos/sip.hpp"

namespace p3at::arcos {

namespace {

// Five strings of this length, their terminators and the 72 fixed bytes fit in one payload.
constexpr std::size_t kMaxConfigString = 32;

// The wire order of §6, written once and shared by the encoder and decoder.
// `Config` is ConfigPacket or const ConfigPacket.
template <class Config, class Visitor>
void visit_fields(Config& c, Visitor& v) {
  v(c.robot_class);
  v(c.subclass);
  v(c.serial_number);
  v(c.spare);
  v(c.top_rot_vel);
  v(c.top_trans_vel);
  v(c.top_rot_accel);
  v(c.top_trans_accel);
  v(c.max_pwm);
  v(c.name);
  v(c.sip_cycle_ms);
  v(c.host_baud);
  v(c.aux_baud);
  v(c.gripper);
  v(c.front_sonar);
  v(c.rear_sonar);
  v(c.low_battery);
  v(c.revcount);
  v(c.watchdog_ms);
  v(c.flag_byte);
  v(c.stall_pwm);
  v(c.stall_time);
  v(c.joy_trans_vel);
  v(c.joy_rot_vel);
  v(c.rot_vel_max);
  v(c.trans_vel_max);
  v(c.rot_accel);
  v(c.rot_decel);
  v(c.rot_kp);
  v(c.rot_kv);
  v(c.rot_ki);
  v(c.trans_accel);
  v(c.trans_decel);
  v(c.trans_kp);
  v(c.trans_kv);
  v(c.trans_ki);
  v(c.front_bumpers);
  v(c.rear_bumpers);
  v(c.charger_type);
  v(c.sonar_cycle);
  v(c.auto_baud);
  v(c.gyro_type);
  v(c.drift_factor);
  v(c.aux2_baud);
  v(c.aux3_baud);
  v(c.ticks_per_mm);
  v(c.shutdown_voltage);
  v(c.firmware_version);
}

struct FieldWriter {
  detail::PayloadWriter out;
  void operator()(const std::string& s) { out.cstring(s, kMaxConfigString); }
  void operator()(std::uint8_t x) { out.u8(x); }
  void operator()(std::uint16_t x) { out.u16(x); }
  void operator()(std::int16_t x) { out.s16(x); }
};

struct FieldReader {
  explicit FieldReader(std::span<const std::uint8_t> bytes) : in(bytes) {}
  detail::PayloadReader in;
  bool truncated = false;
  int whole = 0;

  template <class T>
  void operator()(T& field) {
    // After the first short field everything else is missing and stays 0 / empty.
    if (truncated) return;
    if (read(field)) {
      ++whole;
    } else {
      truncated = true;
    }
  }
  bool read(std::string& s) { return in.cstring(s); }
  bool read(std::uint8_t& x) { return in.u8(x); }
  bool read(std::uint16_t& x) { return in.u16(x); }
  bool read(std::int16_t& x) { return in.s16(x); }
};

}  // namespace

Frame encode_config(const ConfigPacket& config) {
  FieldWriter writer;
  visit_fields(config, writer);
  return encode_frame(kConfigPacket, writer.out.bytes());
}

ConfigPacket decode_config(const Packet& packet, int* fields_read) {
  ConfigPacket config;
  FieldReader reader(packet.payload());
  visit_fields(config, reader);
  if (fields_read != nullptr) *fields_read = reader.whole;
  return config;
}

ConfigPacket simulator_config(const std::string& name, const std::string& subclass) {
  ConfigPacket c;
  c.robot_class = "Pioneer";
  c.subclass = subclass;
  c.serial_number = "SIM";
  c.name = name;
  // Top values bound what a client may set, so they are at least the current maxima.
  c.top_rot_vel = 300;
  c.top_trans_vel = 3000;
  c.top_rot_accel = 300;
  c.top_trans_accel = 1000;
  c.max_pwm = 1000;
  c.sip_cycle_ms = 100;
  c.front_sonar = 1;
  c.rear_sonar = 1;
  c.watchdog_ms = 2000;
  c.rot_vel_max = 150;
  c.trans_vel_max = 3000;
  c.rot_accel = 100;
  c.rot_decel = 100;
  c.trans_accel = 300;
  c.trans_decel = 300;
  c.sonar_cycle = 40;
  c.firmware_version = "SIM";
  return c;
}

}  // namespace p3at::arcos
