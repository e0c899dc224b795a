#include "p3at/sim/firmware_emulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <sstream>

namespace p3at::sim {
namespace {

using arcos::Command;
using arcos::DecodedCommand;

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr double kAngleUnitsPerRad = 4096.0 / (2.0 * std::numbers::pi);
// A HEAD/DHEAD closer than this to the current heading asks for no motion.
constexpr double kHeadEffectRad = 0.5 * kDegToRad;
constexpr std::uint8_t kBatteryDecivolts = 130;  // a charged 12 V lead-acid pack
constexpr std::int8_t kNoTemperature = -127;
constexpr std::uint16_t kFlagFrontSonar = 1u << 1;
constexpr std::uint16_t kFlagRearSonar = 1u << 2;

std::int16_t to_s16(double value) {
  return static_cast<std::int16_t>(std::clamp(std::lround(value), -32768L, 32767L));
}

std::uint16_t to_u16(double value) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(value), 0L, 65535L));
}

// A 15-bit wrapping position counter, as the firmware reports it.
std::uint16_t to_counter15(double value) {
  return static_cast<std::uint16_t>(static_cast<std::uint64_t>(std::llround(value)) & 0x7FFFu);
}

bool is_known(std::uint8_t number) {
  switch (static_cast<Command>(number)) {
    case Command::pulse:
    case Command::open:
    case Command::close:
    case Command::polling:
    case Command::enable:
    case Command::seta:
    case Command::setv:
    case Command::seto:
    case Command::move:
    case Command::rotate:
    case Command::setrv:
    case Command::vel:
    case Command::head:
    case Command::dhead:
    case Command::say:
    case Command::config:
    case Command::encoder:
    case Command::rvel:
    case Command::setra:
    case Command::sonar:
    case Command::stop:
    case Command::vel2:
    case Command::bumpstall:
    case Command::hostbaud:
    case Command::estop:
    case Command::gyro:
    case Command::batteryinfo:
    case Command::reset:
      return true;
  }
  return false;
}

}  // namespace

std::string format_stats(const FirmwareStats& s) {
  std::ostringstream out;
  out << "connections=" << s.connections << " packets=" << s.packets_received << " bad_packets=" << s.bad_packets
      << " garbage_bytes=" << s.garbage_bytes << " unknown_commands=" << s.unknown_commands
      << " motion_commands=" << s.motion_commands << " watchdog_trips=" << s.watchdog_trips
      << " sips=" << s.sips_sent << " injected_drops=" << s.injected_drops;
  return out.str();
}

FirmwareEmulator::FirmwareEmulator(World& world, std::size_t robot_index, const hal::Clock& io_clock, LogSink log)
    : world_(world),
      robot_index_(robot_index),
      io_clock_(io_clock),
      log_(std::move(log)),
      params_(arcos::RobotParams::for_subclass(world.robot(robot_index).config().subclass)) {}

void FirmwareEmulator::log(const std::string& line) const {
  if (log_) log_(line);
}

void FirmwareEmulator::attach(std::unique_ptr<hal::ByteStream> stream) {
  if (!stream) return;
  if (stream_) drop("replaced");
  stream_ = std::move(stream);
  decoder_ = arcos::PacketDecoder{};
  phase_ = Phase::idle;
  sonar_on_ = true;
  ++stats_.connections;
  log("connect robot=" + robot().name() + " peer=" + stream_->describe() +
      " connections=" + std::to_string(stats_.connections));
}

void FirmwareEmulator::drop(const char* reason) {
  if (!stream_) return;
  // Whatever ended the session, the robot must not keep driving unattended.
  MotionController& c = robot().controller();
  c.enable_motors(false);
  c.set_watchdog(false, world_.time_us());
  was_halted_ = false;
  const arcos::DecoderStats& d = decoder_.stats();
  past_decoders_.packets += d.packets;
  past_decoders_.bad_header += d.bad_header;
  past_decoders_.bad_checksum += d.bad_checksum;
  past_decoders_.bad_count += d.bad_count;
  past_decoders_.timeouts += d.timeouts;
  past_decoders_.discarded_bytes += d.discarded_bytes;
  decoder_ = arcos::PacketDecoder{};
  stream_->close();
  stream_.reset();
  phase_ = Phase::idle;
  log("disconnect robot=" + robot().name() + " reason=" + reason);
}

void FirmwareEmulator::send(const arcos::Frame& frame) {
  if (!stream_) return;
  const Status st = stream_->write_all(frame.span());
  if (!st.ok()) pending_drop_ = st.error().code == Error::Code::closed ? "peer-closed" : "write-error";
}

void FirmwareEmulator::poll() {
  std::array<std::uint8_t, 512> buffer{};
  while (stream_ && !pending_drop_) {
    auto got = stream_->read_some(buffer, 0);
    if (!got.ok()) {
      pending_drop_ = got.error().code == Error::Code::closed ? "peer-closed" : "read-error";
      break;
    }
    if (*got == 0) {
      decoder_.expire(io_clock_.now_us());
      break;
    }
    decoder_.feed(std::span<const std::uint8_t>(buffer.data(), *got), io_clock_.now_us(),
                  [this](const arcos::Packet& p) {
                    // Bytes after a CLOSE in the same read belong to a finished session.
                    if (!pending_drop_) handle(p);
                  });
  }
  if (pending_drop_) {
    const char* reason = pending_drop_;
    pending_drop_ = nullptr;
    drop(reason);
  }
}

void FirmwareEmulator::on_cycle() {
  const MotionController& c = robot().controller();
  if (c.watchdog_halted() && !was_halted_) {
    log("watchdog robot=" + robot().name() + " state=tripped trips=" + std::to_string(c.stats().watchdog_trips));
  }
  was_halted_ = c.watchdog_halted();
  if (phase_ == Phase::open && stream_) {
    send(arcos::encode_sip(make_sip()));
    if (!pending_drop_) ++stats_.sips_sent;
  }
  if (pending_drop_) {
    const char* reason = pending_drop_;
    pending_drop_ = nullptr;
    drop(reason);
  }
}

FirmwareStats FirmwareEmulator::stats() const {
  FirmwareStats s = stats_;
  const arcos::DecoderStats& d = decoder_.stats();
  s.bad_packets = past_decoders_.errors() + d.errors();
  s.garbage_bytes = past_decoders_.discarded_bytes + d.discarded_bytes;
  s.motion_commands = robot().controller().stats().motion_commands;
  s.watchdog_trips = robot().controller().stats().watchdog_trips;
  return s;
}

void FirmwareEmulator::handle(const arcos::Packet& packet) {
  ++stats_.packets_received;
  if (injected_drop(packet)) return;
  if (phase_ == Phase::open) {
    handle_command(packet);
  } else {
    handle_handshake(packet);
  }
}

bool FirmwareEmulator::injected_drop(const arcos::Packet& packet) {
  // Command 1 is OPEN once SYNC2 has been answered (before that it is SYNC1).
  const bool is_open = packet.id == static_cast<std::uint8_t>(Command::open) &&
                       (phase_ == Phase::sync2 || phase_ == Phase::open);
  // Only an ENABLE with an integer argument switches the motors (handle_command).
  const arcos::DecodedCommand cmd = arcos::decode_command(packet);
  const bool is_enable = phase_ == Phase::open && packet.id == static_cast<std::uint8_t>(Command::enable) &&
                         cmd.kind == arcos::DecodedCommand::ArgKind::integer;
  const bool is_enable_on = is_enable && cmd.value != 0;
  int* left = is_open ? &opens_to_drop_ : is_enable_on ? &enables_to_drop_ : is_enable ? &disables_to_drop_ : nullptr;
  if (left == nullptr || *left == 0) return false;
  --*left;
  ++stats_.injected_drops;
  log(std::string("fault robot=") + robot().name() + " dropped=" + (is_open ? "OPEN" : is_enable_on ? "ENABLE" : "DISABLE") +
      " left=" + std::to_string(*left));
  return true;
}

void FirmwareEmulator::handle_handshake(const arcos::Packet& packet) {
  const SimRobot& r = robot();
  switch (packet.id) {
    case arcos::kSync0:
      // SYNC0 always restarts the handshake: a client that lost a reply begins again.
      send(arcos::encode_command(arcos::kSync0));
      phase_ = Phase::sync0;
      return;
    case arcos::kSync1:
      if (phase_ == Phase::sync2) {
        // After SYNC2, command 1 is OPEN.
        phase_ = Phase::open;
        robot().controller().set_watchdog(watchdog_ms_ > 0, world_.time_us(),
                                          static_cast<std::int64_t>(watchdog_ms_) * 1000);
        was_halted_ = false;
        log("open robot=" + r.name());
        return;
      }
      if (phase_ == Phase::sync0 || phase_ == Phase::sync1) {
        send(arcos::encode_command(arcos::kSync1));
        phase_ = Phase::sync1;
      }
      return;
    case arcos::kSync2:
      if (phase_ == Phase::sync1 || phase_ == Phase::sync2) {
        send(arcos::encode_identity({r.name(), "Pioneer", r.config().subclass}));
        phase_ = Phase::sync2;
      }
      return;
    default:
      // Nothing but the handshake is answered before OPEN.
      if (!is_known(packet.id)) ++stats_.unknown_commands;
      return;
  }
}

void FirmwareEmulator::handle_command(const arcos::Packet& packet) {
  SimRobot& r = robot();
  MotionController& c = r.controller();
  c.note_command(world_.time_us());
  if (was_halted_ && !c.watchdog_halted()) {
    log("watchdog robot=" + r.name() + " state=resumed");
    was_halted_ = false;
  }
  if (!is_known(packet.id)) {
    ++stats_.unknown_commands;
    return;
  }
  const DecodedCommand cmd = arcos::decode_command(packet);
  const bool has_int = cmd.kind == DecodedCommand::ArgKind::integer;
  const double value = static_cast<double>(cmd.value);
  switch (static_cast<Command>(packet.id)) {
    case Command::pulse:
    case Command::open:
      return;
    case Command::close:
      pending_drop_ = "close-command";
      return;
    case Command::enable:
      if (has_int) c.enable_motors(cmd.value != 0);
      return;
    case Command::seta:
      if (has_int) c.set_trans_accel(value / 1000.0);
      return;
    case Command::setv:
      if (has_int) c.set_max_trans_vel(value / 1000.0);
      return;
    case Command::setra:
      if (has_int) c.set_rot_accel(value * kDegToRad);
      return;
    case Command::setrv:
      if (has_int) c.set_max_rot_vel(value * kDegToRad);
      return;
    case Command::seto:
      r.reset_odometry();
      return;
    case Command::vel:
      if (!has_int) return;
      if (cmd.value != 0) c.count_motion_command();
      c.command_trans_vel(value / 1000.0);
      return;
    case Command::rvel:
    case Command::rotate:
      if (!has_int) return;
      if (cmd.value != 0) c.count_motion_command();
      c.command_rot_vel(value * kDegToRad);
      return;
    case Command::vel2: {
      if (!has_int) return;
      const arcos::Vel2 wheels = arcos::unpack_vel2(cmd.value);
      const double left = wheels.left_units * params_.vel2_divisor / 1000.0;
      const double right = wheels.right_units * params_.vel2_divisor / 1000.0;
      if (wheels.left_units != 0 || wheels.right_units != 0) c.count_motion_command();
      c.command_trans_vel((left + right) / 2.0);
      c.command_rot_vel((right - left) / kNominalTrackM);
      return;
    }
    case Command::head: {
      if (!has_int) return;
      const double target = value * kDegToRad;
      if (std::abs(wrap_angle(target - r.odometry().theta_rad)) >= kHeadEffectRad) c.count_motion_command();
      c.command_heading(target);
      return;
    }
    case Command::dhead: {
      if (!has_int) return;
      const double delta = value * kDegToRad;
      if (std::abs(wrap_angle(delta)) >= kHeadEffectRad) c.count_motion_command();
      c.command_heading(r.odometry().theta_rad + delta);
      return;
    }
    case Command::move:
      if (!has_int) return;
      if (cmd.value != 0) c.count_motion_command();
      c.command_move(value / 1000.0, r.odometry_distance_m());
      return;
    case Command::stop:
      c.stop();
      return;
    case Command::estop:
      c.emergency_stop();
      return;
    case Command::sonar:
      if (has_int) sonar_on_ = cmd.value != 0;
      return;
    case Command::config:
      send(arcos::encode_config(make_config()));
      return;
    case Command::polling:      // sonar order: every sonar is fired every cycle anyway
    case Command::say:          // no buzzer
    case Command::batteryinfo:  // no battery packet in the simulator
    case Command::encoder:
    case Command::bumpstall:
    case Command::hostbaud:
    case Command::gyro:
    case Command::reset:
      return;
  }
}

arcos::Sip FirmwareEmulator::make_sip() const {
  const SimRobot& r = robot();
  const MotionController& c = r.controller();
  arcos::Sip sip;
  sip.moving = r.moving();
  const Pose& odo = r.odometry();
  sip.xpos = to_counter15(odo.x_m * 1000.0 / params_.dist_conv);
  sip.ypos = to_counter15(odo.y_m * 1000.0 / params_.dist_conv);
  sip.thpos = to_s16(odo.theta_rad * kAngleUnitsPerRad);
  sip.left_vel = to_s16(r.left_wheel_mps() * 1000.0 / params_.vel_conv);
  sip.right_vel = to_s16(r.right_wheel_mps() * 1000.0 / params_.vel_conv);
  sip.battery = kBatteryDecivolts;
  sip.stall_bumpers = static_cast<std::uint16_t>((r.left_stall() ? arcos::kLeftStall : 0u) |
                                                 (r.right_stall() ? arcos::kRightStall : 0u));
  sip.control = to_s16((c.in_heading_mode() ? c.heading_target_rad() : odo.theta_rad) * kAngleUnitsPerRad);
  std::uint16_t flags = 0;
  if (c.motors_enabled()) flags |= arcos::kFlagMotorsEnabled;
  if (sonar_on_) flags |= kFlagFrontSonar | kFlagRearSonar;
  if (c.estop()) flags |= arcos::kFlagEstop;
  sip.flags = flags;
  sip.compass = 0;
  if (sonar_on_) {
    const auto& ranges = r.sonar_ranges_m();
    sip.sonar_count = static_cast<std::uint8_t>(ranges.size());
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      sip.sonar[i] = arcos::SonarRaw{static_cast<std::uint8_t>(i), to_u16(ranges[i] * 1000.0 / params_.range_conv)};
    }
  }
  sip.io = arcos::SipIo{};
  sip.battery_x10 = kBatteryDecivolts;
  sip.charge_state = 0;
  sip.rotvel = to_s16(r.odometry_rot_vel_radps() * kRadToDeg * 10.0);
  sip.fault_flags = 0;
  sip.latvel = 0;
  sip.temperature = kNoTemperature;
  sip.state_of_charge = 0;
  sip.controller_time_us = static_cast<std::uint32_t>(static_cast<std::uint64_t>(world_.time_us()) & 0xFFFFFFFFu);
  sip.flags3 = 0;
  return sip;
}

arcos::ConfigPacket FirmwareEmulator::make_config() const {
  const SimRobot& r = robot();
  const MotionController& c = r.controller();
  const MotionLimits& top = c.limits();
  arcos::ConfigPacket cfg = arcos::simulator_config(r.name(), r.config().subclass);
  // Velocity and acceleration fields from this robot's real limits; never 0,
  // or ARIA would clamp every command to nothing.
  const auto nonzero = [](double v) { return std::max<std::uint16_t>(1, to_u16(v)); };
  cfg.top_trans_vel = nonzero(top.max_trans_vel_mps * 1000.0);
  cfg.top_rot_vel = nonzero(top.max_rot_vel_degps);
  cfg.trans_vel_max = nonzero(c.max_trans_vel_mps() * 1000.0);
  cfg.rot_vel_max = nonzero(c.max_rot_vel_radps() * kRadToDeg);
  cfg.trans_accel = nonzero(c.trans_accel_mps2() * 1000.0);
  cfg.trans_decel = nonzero(c.trans_decel_mps2() * 1000.0);
  cfg.rot_accel = nonzero(c.rot_accel_radps2() * kRadToDeg);
  cfg.rot_decel = nonzero(c.rot_decel_radps2() * kRadToDeg);
  cfg.watchdog_ms = static_cast<std::uint16_t>(std::min(watchdog_ms_, 65535));
  cfg.top_trans_accel = std::max({cfg.top_trans_accel, cfg.trans_accel, cfg.trans_decel});
  cfg.top_rot_accel = std::max({cfg.top_rot_accel, cfg.rot_accel, cfg.rot_decel});
  return cfg;
}

}  // namespace p3at::sim
