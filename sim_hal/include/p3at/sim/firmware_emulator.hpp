#pragma once
/// The robot side of ARCOS for one simulated robot, over any ByteStream
/// (docs/arcos-protocol.md §3, §4, §9): SYNC handshake, OPEN, a SIP every
/// cycle, CONFIG, the motion commands, CLOSE, and the 2 s command watchdog.
/// p3at_sim serves one per robot on TCP; tests drive it over in-memory streams.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/sip.hpp"
#include "p3at/sim/world.hpp"

namespace p3at::sim {

/// Per-robot counters over all connections. Never reset.
struct FirmwareStats {
  std::uint64_t connections = 0;       ///< clients attached
  std::uint64_t packets_received = 0;  ///< valid packets (any command, any phase)
  std::uint64_t bad_packets = 0;       ///< dropped by the decoder: bad header, checksum, count, timeout
  std::uint64_t garbage_bytes = 0;     ///< bytes skipped while hunting for a header
  std::uint64_t unknown_commands = 0;  ///< valid packets with a command number we do not know
  std::uint64_t motion_commands = 0;   ///< see ControllerStats::motion_commands
  std::uint64_t watchdog_trips = 0;    ///< see ControllerStats::watchdog_trips
  std::uint64_t sips_sent = 0;
  std::uint64_t injected_drops = 0;    ///< commands ignored on purpose (drop_first_commands)
};

/// One line per stats field, "key=value" separated by spaces (for logs).
std::string format_stats(const FirmwareStats& stats);

class FirmwareEmulator {
 public:
  /// Receives one log line per event (connect, open, close, watchdog), without a
  /// trailing newline, e.g. "connect robot=robot1 peer=tcp://127.0.0.1:40000".
  using LogSink = std::function<void(const std::string& line)>;

  /// Serves `world.robot(robot_index)`. `io_clock` times the byte stream (the
  /// decoder's inter-byte timeout: wall time on TCP); the world's clock times
  /// everything the robot does (SIPs, watchdog). Both must outlive this object.
  FirmwareEmulator(World& world, std::size_t robot_index, const hal::Clock& io_clock, LogSink log = {});
  FirmwareEmulator(const FirmwareEmulator&) = delete;
  FirmwareEmulator& operator=(const FirmwareEmulator&) = delete;

  /// The command watchdog armed at OPEN, in simulated time; 0 disables it.
  /// Default 2000 ms, as on a real P3-AT. Applies from the next OPEN.
  void set_watchdog_ms(int watchdog_ms) { watchdog_ms_ = watchdog_ms > 0 ? watchdog_ms : 0; }
  int watchdog_ms() const { return watchdog_ms_; }

  /// Fault injection for tests of the client's resends: ignore the first
  /// `opens` OPEN, the first `enables` ENABLE 1 and the first `disables` ENABLE 0
  /// commands this robot receives (over all connections, whether sent while
  /// connecting or later), as if the line had lost them. Each is logged.
  void drop_first_commands(int opens, int enables, int disables = 0) {
    opens_to_drop_ = opens > 0 ? opens : 0;
    enables_to_drop_ = enables > 0 ? enables : 0;
    disables_to_drop_ = disables > 0 ? disables : 0;
  }

  /// Takes ownership of a newly accepted client. A current client is dropped first.
  void attach(std::unique_ptr<hal::ByteStream> stream);

  /// True while a client is attached.
  bool connected() const { return stream_ != nullptr; }

  /// True after OPEN, until CLOSE or disconnect: SIPs are streamed.
  bool is_open() const { return phase_ == Phase::open; }

  /// Reads everything that has arrived, without blocking, and handles each
  /// command. A closed or failing stream is dropped (the robot halts).
  void poll();

  /// Call once after every World::step(): sends this cycle's SIP when open,
  /// and logs watchdog trips.
  void on_cycle();

  /// Counters, including the robot controller's motion-command and watchdog counts.
  FirmwareStats stats() const;

  SimRobot& robot() { return world_.robot(robot_index_); }
  const SimRobot& robot() const { return world_.robot(robot_index_); }

  /// The SIP the robot would send now (also used by tests).
  arcos::Sip make_sip() const;

  /// The config packet the robot answers CONFIG with.
  arcos::ConfigPacket make_config() const;

 private:
  /// Handshake progress: a SYNCn is answered once SYNC0..n-1 were; after SYNC2
  /// command 1 is OPEN.
  enum class Phase { idle, sync0, sync1, sync2, open };

  void handle(const arcos::Packet& packet);
  /// True when `packet` is one drop_first_commands() asked to lose.
  bool injected_drop(const arcos::Packet& packet);
  void handle_handshake(const arcos::Packet& packet);
  void handle_command(const arcos::Packet& packet);
  void send(const arcos::Frame& frame);
  void drop(const char* reason);
  void log(const std::string& line) const;

  World& world_;
  std::size_t robot_index_;
  const hal::Clock& io_clock_;
  LogSink log_;
  arcos::RobotParams params_;
  std::unique_ptr<hal::ByteStream> stream_;
  arcos::PacketDecoder decoder_;
  arcos::DecoderStats past_decoders_{};  ///< sums of the decoders of closed connections
  Phase phase_ = Phase::idle;
  bool sonar_on_ = true;
  int watchdog_ms_ = 2000;
  const char* pending_drop_ = nullptr;   ///< set while handling a packet that ends the session
  bool was_halted_ = false;
  int opens_to_drop_ = 0;
  int enables_to_drop_ = 0;
  int disables_to_drop_ = 0;
  FirmwareStats stats_{};
};

}  // namespace p3at::sim
