#pragma once
// A FirmwareEmulator on one simulated robot, driven by a client over an
// in-memory stream pair: the test plays ARIA's part byte for byte.

#include <memory>
#include <string>
#include <vector>

#include "memory_stream.hpp"  // tests/support: the shared in-memory stream pair
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/sip.hpp"
#include "p3at/sim/firmware_emulator.hpp"
#include "sim_test_util.hpp"

namespace p3at::sim::test {

struct EmulatorHarness {
  explicit EmulatorHarness(const RobotConfig& robot = exact_robot())
      : world(world_of({robot})), fw(world, 0, world.clock(), [this](const std::string& l) { logs.push_back(l); }) {
    connect();
  }

  /// A new client connection (the old client end is kept until replaced).
  void connect() {
    p3at::test::MemoryPipe pipe;
    client = pipe.make_a();
    decoder = arcos::PacketDecoder{};
    fw.attach(pipe.make_b());
  }

  void send(const arcos::Frame& frame) {
    REQUIRE(client->write_all(frame.span()).ok());
    fw.poll();
  }
  void send(arcos::Command c) { send(arcos::encode_command(c)); }
  void send(arcos::Command c, int value) { send(arcos::encode_command(c, value)); }
  void send_raw(const std::vector<std::uint8_t>& bytes) {
    REQUIRE(client->write_all(bytes).ok());
    fw.poll();
  }

  /// Every packet the robot has sent since the last call.
  std::vector<arcos::Packet> receive() {
    std::vector<arcos::Packet> out;
    std::array<std::uint8_t, 1024> buf{};
    for (;;) {
      auto got = client->read_some(buf, 0);
      if (!got.ok() || *got == 0) break;
      decoder.feed(std::span<const std::uint8_t>(buf.data(), *got), world.clock().now_us(),
                   [&](const arcos::Packet& p) { out.push_back(p); });
    }
    return out;
  }

  /// Only the SIPs among what arrived.
  std::vector<arcos::Sip> receive_sips() {
    std::vector<arcos::Sip> sips;
    for (const auto& p : receive()) {
      if (p.id == arcos::kSipMoving || p.id == arcos::kSipStopped) {
        auto sip = arcos::decode_sip(p);
        REQUIRE(sip.ok());
        sips.push_back(*sip);
      }
    }
    return sips;
  }

  /// `n` controller cycles as p3at_sim runs them: read commands, step, send SIPs.
  void cycle(int n = 1) {
    for (int i = 0; i < n; ++i) {
      fw.poll();
      world.step();
      fw.on_cycle();
    }
  }

  /// `n` cycles with a PULSE every 500 ms, like ARIA's keep-alive, so the
  /// watchdog stays quiet during long motions.
  void drive(int n) {
    for (int i = 0; i < n; ++i) {
      if (i % 5 == 4) send(arcos::Command::pulse);
      cycle(1);
    }
  }

  void handshake() {
    send(arcos::encode_command(arcos::kSync0));
    send(arcos::encode_command(arcos::kSync1));
    send(arcos::encode_command(arcos::kSync2));
    (void)receive();
  }
  void open() {
    handshake();
    send(arcos::Command::open, 1);
  }

  World world;
  std::vector<std::string> logs;
  FirmwareEmulator fw;
  std::unique_ptr<p3at::test::MemoryStream> client;
  arcos::PacketDecoder decoder;
};

inline bool any_log_contains(const std::vector<std::string>& logs, const std::string& needle) {
  for (const auto& l : logs) {
    if (l.find(needle) != std::string::npos) return true;
  }
  return false;
}

}  // namespace p3at::sim::test
