#pragma once
// A robot that answers the way docs/arcos-protocol.md says a Pioneer does,
// written from the reference and independent of our firmware emulator, so the
// bridge is tested against the protocol rather than against our own simulator.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fake_clock.hpp"
#include "memory_stream.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/sip.hpp"

namespace p3at::test {

struct ReceivedCommand {
  std::int64_t at_us;
  std::uint8_t number;
  int value;
  bool has_value;
};

class ScriptedRobot {
 public:
  // Behaviour switches.
  std::string name = "AMRISim";
  std::string subclass = "p3at";
  bool answer_config = true;
  bool still_open_at_start = false;  // streams SIPs before any SYNC, like a robot left open
  int syncs_to_ignore = 0;           // drop this many SYNC0s before answering
  bool silent = false;               // never answers anything
  bool garbage_replies = false;      // answers every command with text, not ARCOS packets (wrong device)
  bool corrupt_replies = false;      // answers SYNCs with packets whose checksum is wrong (noisy line)
  bool sips_paused = false;          // opened, but SIPs stop (link loss)
  int opens_to_ignore = 0;           // lose this many OPENs (a lossy line)
  int enables_to_ignore = 0;         // lose this many ENABLE 1s
  int disables_to_ignore = 0;        // lose this many ENABLE 0s
  bool estop_pressed = false;        // the e-stop button is in: ENABLE has no effect, SIPs say so
  std::uint16_t start_x = 0x7F00;    // near the 15-bit wrap
  std::uint16_t start_y = 100;
  std::int16_t start_th = 0;
  std::int64_t sip_period_us = 100'000;  // shorter = a simulator running faster than real time

  // What the robot saw and does.
  std::vector<ReceivedCommand> received;
  bool opened = false;
  bool enabled = false;
  int vel_mm_s = 0;
  int rvel_deg_s = 0;
  double x_units = 0, y_units = 0, th_units = 0;  // firmware counters, unwrapped
  std::uint8_t battery_x10 = 130;

  ScriptedRobot(FakeClock& clock) : clock_(clock) {}

  /// Attaches a fresh connection (a new TCP session).
  void attach(MemoryStream* stream) {
    stream_ = stream;
    decoder_ = arcos::PacketDecoder{};
    opened = still_open_at_start;
    synced_ = false;
    next_sip_us_ = clock_.now_us() + 100'000;
    x_units = start_x;
    y_units = start_y;
    th_units = start_th;
  }

  /// Processes what arrived and emits SIPs due by now.
  void run() {
    if (!stream_) return;
    std::uint8_t buf[512];
    while (true) {
      auto got = stream_->read_some(std::span<std::uint8_t>(buf, sizeof buf), 0);
      if (!got || got.value() == 0) break;
      decoder_.feed(std::span<const std::uint8_t>(buf, got.value()), clock_.now_us(),
                    [this](const arcos::Packet& p) { handle(p); });
    }
    while (opened && !silent && clock_.now_us() >= next_sip_us_) {
      integrate(0.1);
      if (!sips_paused) send(arcos::encode_sip(make_sip()));
      next_sip_us_ += sip_period_us;
    }
  }

  std::vector<std::uint8_t> command_numbers() const {
    std::vector<std::uint8_t> out;
    for (const auto& c : received) out.push_back(c.number);
    return out;
  }

  arcos::Sip make_sip() const {
    arcos::Sip sip;
    sip.moving = vel_mm_s != 0 || rvel_deg_s != 0;
    sip.xpos = static_cast<std::uint16_t>(static_cast<long>(x_units) & 0x7FFF);
    sip.ypos = static_cast<std::uint16_t>(static_cast<long>(y_units) & 0x7FFF);
    long th = static_cast<long>(th_units) % 4096;
    if (th > 2048) th -= 4096;
    if (th < -2048) th += 4096;
    sip.thpos = static_cast<std::int16_t>(th);
    sip.left_vel = static_cast<std::int16_t>(vel_mm_s);
    sip.right_vel = static_cast<std::int16_t>(vel_mm_s);
    sip.battery = 130;
    sip.flags = static_cast<std::uint16_t>((enabled ? arcos::kFlagMotorsEnabled : 0) |
                                           (estop_pressed ? arcos::kFlagEstop : 0));
    sip.sonar_count = 2;
    sip.sonar[0] = {3, 1234};
    sip.sonar[1] = {12, 4000};
    sip.io = arcos::SipIo{};
    sip.battery_x10 = battery_x10;
    sip.charge_state = 0;
    sip.rotvel = static_cast<std::int16_t>(rvel_deg_s * 10);
    return sip;
  }

 private:
  void send(const arcos::Frame& f) { (void)stream_->write_all(f.span()); }

  void integrate(double dt_s) {
    if (!enabled) return;
    const double dist_conv = subclass == "p3at" ? 0.465 : 1.0;
    const double th_rad = th_units * 2 * 3.14159265358979323846 / 4096.0;
    x_units += vel_mm_s * dt_s * std::cos(th_rad) / dist_conv;
    y_units += vel_mm_s * dt_s * std::sin(th_rad) / dist_conv;
    th_units += rvel_deg_s * dt_s * 4096.0 / 360.0;
  }

  void handle(const arcos::Packet& p) {
    const auto cmd = arcos::decode_command(p);
    received.push_back({clock_.now_us(), p.id, cmd.value, cmd.kind == arcos::DecodedCommand::ArgKind::integer});
    if (silent) return;
    if (garbage_replies) {
      static constexpr std::uint8_t kText[] = {'A', 'T', 'Z', '\r', '\n', 'O', 'K', '\r', '\n'};
      (void)stream_->write_all(std::span<const std::uint8_t>(kText, sizeof kText));
      return;
    }
    if (corrupt_replies) {
      const arcos::Frame frame = arcos::encode_frame(p.id, {});
      std::vector<std::uint8_t> bytes(frame.span().begin(), frame.span().end());
      bytes.back() ^= 0x55;
      (void)stream_->write_all(bytes);
      return;
    }
    if (!opened) {
      if (p.id == arcos::kSync0 && syncs_to_ignore > 0) {
        --syncs_to_ignore;
        return;
      }
      // Numbers 0, 1, 2 are SYNCs until SYNC2 has been answered; then 1 is OPEN.
      if (synced_ && p.id == static_cast<std::uint8_t>(arcos::Command::open) && opens_to_ignore > 0) {
        --opens_to_ignore;
      } else if (synced_ && p.id == static_cast<std::uint8_t>(arcos::Command::open)) {
        opened = true;
        next_sip_us_ = clock_.now_us() + 100'000;
      } else if (p.id == arcos::kSync0 || p.id == arcos::kSync1) {
        synced_ = false;
        send(arcos::encode_frame(p.id, {}));
      } else if (p.id == arcos::kSync2) {
        synced_ = true;
        send(arcos::encode_identity({name, "Pioneer", subclass}));
      }
      return;
    }
    using arcos::Command;
    const auto is = [&p](Command c) { return p.id == static_cast<std::uint8_t>(c); };
    if (is(Command::close)) {
      opened = false;
      synced_ = false;
      enabled = false;
      vel_mm_s = rvel_deg_s = 0;
    } else if (is(Command::enable) && cmd.value != 0 && enables_to_ignore > 0) {
      --enables_to_ignore;
    } else if (is(Command::enable) && cmd.value == 0 && disables_to_ignore > 0) {
      --disables_to_ignore;
    } else if (is(Command::enable)) {
      enabled = cmd.value != 0 && !estop_pressed;
    } else if (is(Command::vel)) {
      vel_mm_s = cmd.value;
    } else if (is(Command::rvel)) {
      rvel_deg_s = cmd.value;
    } else if (is(Command::stop) || is(Command::estop)) {
      vel_mm_s = rvel_deg_s = 0;
    } else if (is(Command::config)) {
      if (answer_config) send(arcos::encode_config(arcos::simulator_config(name, subclass)));
    }
    // Anything else is ignored, as the reference requires of a robot.
  }

  FakeClock& clock_;
  MemoryStream* stream_ = nullptr;
  arcos::PacketDecoder decoder_;
  std::int64_t next_sip_us_ = 0;
  bool synced_ = false;
};

}  // namespace p3at::test
