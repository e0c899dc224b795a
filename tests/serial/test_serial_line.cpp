// The serial backend on a real UART (serial rig, docs/hal.md): the tty is the
// kernel's 8250 driver on an emulated 16550; its far end is p3at_sim or an
// in-process peer reached through QEMU. Every supported baud rate opens and
// talks ARCOS; an unsupported one is refused at once; a far end that answers
// noise (what a wrong baud rate looks like) fails the handshake with a clear
// message; a write larger than the driver's buffer is taken in pieces and
// arrives whole; reads that return a few bytes at a time reassemble.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "p3at/bridge/arcos_client.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/packet.hpp"
#include "rig_sim.hpp"
#include "serial_rig.hpp"

using namespace p3at;
using namespace p3at::test::serial_rig;
using p3at::test::ChildProcess;
using p3at::test::scratch_path;

namespace {

constexpr int kBauds[] = {9600, 19200, 38400, 57600, 115200};

bool contains(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

/// The 8250 driver's own transmit and receive counters for the tty (/proc/tty/driver/serial).
struct UartCounters {
  std::string line;  ///< the driver's whole line, for messages
  std::string uart;
  long long tx = -1, rx = -1;
};
UartCounters uart_counters() {
  const std::string dev = device();
  const std::string line_no = dev.substr(dev.find_last_not_of("0123456789") + 1);
  std::ifstream in("/proc/tty/driver/serial");
  UartCounters c;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(line_no + ": ", 0) != 0) continue;
    c.line = line;
    std::istringstream fields(line.substr(line_no.size() + 2));
    for (std::string f; fields >> f;) {
      if (f.rfind("uart:", 0) == 0) c.uart = f.substr(5);
      if (f.rfind("tx:", 0) == 0) c.tx = std::stoll(f.substr(3));
      if (f.rfind("rx:", 0) == 0) c.rx = std::stoll(f.substr(3));
    }
  }
  return c;
}

/// The i-th frame of a deterministic stream: alternating SIP types, payloads of 0..61 bytes.
arcos::Frame nth_frame(std::size_t i) {
  std::vector<std::uint8_t> payload(i % 62);
  for (std::size_t k = 0; k < payload.size(); ++k) payload[k] = static_cast<std::uint8_t>(i * 7 + k * 13);
  return arcos::encode_frame(static_cast<std::uint8_t>(0x32 + i % 2), payload);
}

bool same_as_nth(const arcos::Packet& p, std::size_t i) {
  const arcos::Frame f = nth_frame(i);
  if (p.id != f.bytes[3] || p.payload_size + 6u != f.size) return false;
  return std::equal(p.payload().begin(), p.payload().end(), f.bytes.begin() + 4);
}

/// The rig's emulated machine can stall a process for longer than ARCOS's
/// 100 ms inter-byte timeout (the host is shared and QEMU emulates the CPU),
/// which would drop a packet for reasons that are not the line's. These tests
/// are about reassembly, so their decoders wait longer; the timeout itself is
/// tested in unit_protocols, and ArcosClient keeps the real one everywhere else.
arcos::PacketDecoder patient_decoder() {
  arcos::DecoderLimits limits;
  limits.inter_byte_timeout_us = 30'000'000;
  return arcos::PacketDecoder(limits);
}

std::vector<std::uint8_t> frames_bytes(std::size_t from, std::size_t to) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = from; i < to; ++i) {
    const auto f = nth_frame(i);
    out.insert(out.end(), f.bytes.begin(), f.bytes.begin() + static_cast<std::ptrdiff_t>(f.size));
  }
  return out;
}

std::unique_ptr<hal::ByteStream> open_line(int baud) {
  auto opened = hal::open_byte_stream(url(baud));
  REQUIRE_MESSAGE(opened.ok(), (opened.ok() ? "" : opened.error().message));
  return std::move(opened).value();
}

}  // namespace

TEST_CASE("the tty under test is a 16550 under the kernel's 8250 driver, and libserialport opens it") {
  const UartCounters before = uart_counters();
  CHECK(before.uart == "16550A");
  REQUIRE(before.tx >= 0);
  auto line = open_line(9600);
  CHECK(line->describe() == url(9600));
  CHECK(driver_baud() == 9600);
  const std::vector<std::uint8_t> bytes(64, 0x55);
  REQUIRE(line->write_all(bytes).ok());
  // The driver counted the bytes it put into the UART's transmit register.
  const auto deadline = steady_ms() + 5000;
  while (uart_counters().tx < before.tx + 64 && steady_ms() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  CHECK(uart_counters().tx >= before.tx + 64);
}

TEST_CASE("every supported baud rate opens the port at that rate and talks ARCOS with p3at_sim") {
  SimOnPeerPort sim;
  REQUIRE_MESSAGE(sim.line_connected(1), sim.process.log());
  hal::SteadyClock clock;
  for (const int baud : kBauds) {
    CAPTURE(baud);
    // No wait between sessions: after CLOSE p3at_sim drops the TCP connection
    // and QEMU reconnects when the port is next opened and read (about 1 s);
    // the client's SYNC retries ride over that, as over a robot that was
    // still open from an earlier client.
    bridge::ClientConfig config;
    config.serial_preamble = true;
    config.auto_reconnect = false;
    config.log_name = "serial_rig";
    bridge::ArcosClient robot([baud] { return hal::open_byte_stream(url(baud)); }, clock, config);
    const auto st = robot.connect();
    REQUIRE_MESSAGE(st.ok(), (st.ok() ? "" : st.error().message));
    CHECK(driver_baud() == baud);
    CHECK(robot.info().identity.robot_class == "Pioneer");
    CHECK(robot.info().identity.subclass.rfind("p3at", 0) == 0);
    CHECK(robot.info().config.has_value());
    const std::uint64_t sips_before = robot.stats().sips;
    for (int i = 0; i < 20 && robot.stats().sips < sips_before + 5; ++i) (void)robot.wait_for_update(250);
    CHECK(robot.stats().sips >= sips_before + 5);
    CHECK(robot.state().link == hal::LinkState::ok);
    CHECK(robot.decoder_stats().bad_checksum == 0);
    MESSAGE("baud " << baud << ": handshake and 5 SIPs, decoder timeouts " << robot.decoder_stats().timeouts);
    CHECK(robot.disconnect().ok());
  }
}

TEST_CASE("an unsupported baud rate is refused at open with the supported ones listed, not a hang") {
  for (const char* baud : {"4800", "230400", "9601"}) {
    CAPTURE(baud);
    const std::string u = "serial://" + device() + "?baud=" + baud;
    const std::int64_t t0 = steady_ms();
    ChildProcess ctl({P3AT_CTL_BIN, u, "status"}, scratch_path("ctl.log"));
    CHECK(ctl.wait_exit(20.0) == 2);  // a malformed --hal URL is a usage error: exit 2 for every binary (README)
    CHECK(steady_ms() - t0 < 10000);
    const std::string out = ctl.log();
    INFO(out);
    CHECK(contains(out, "baud '" + std::string(baud) + "' is not supported (expected one of 9600, 19200, 38400, 57600, 115200)"));
  }
}

TEST_CASE("a far end that answers noise (a wrong baud rate) fails the handshake with a clear message") {
  // With a real line at the wrong rate the UART delivers framing garbage, or
  // nothing. QEMU's UART passes bytes at any rate, so this far end plays the
  // garbage: every byte it receives is answered with noise, some of it 0xFA.
  std::atomic<std::size_t> noise_sent{0};
  FarEnd far([&noise_sent](hal::ByteStream& line, const std::atomic<bool>& stop) {
    std::uint32_t x = 12345;
    std::vector<std::uint8_t> in(256);
    while (!stop) {
      auto got = line.read_some(in, 50);
      if (!got.ok()) return;
      std::vector<std::uint8_t> noise(*got * 2);
      for (auto& b : noise) {
        x = x * 1103515245u + 12345u;
        b = (x >> 24) % 5 == 0 ? 0xFA : static_cast<std::uint8_t>(x >> 16);
      }
      if (!line.write_all(noise).ok()) return;
      noise_sent += noise.size();
    }
  });
  REQUIRE_MESSAGE(far.wait_connected(), far.listen_error());
  const std::int64_t t0 = steady_ms();
  ChildProcess ctl({P3AT_CTL_BIN, url(9600), "status"}, scratch_path("ctl.log"));
  const int rc = ctl.wait_exit(30.0);
  const std::int64_t took_ms = steady_ms() - t0;
  const std::string out = ctl.log();
  INFO(out);
  CHECK(rc == 1);
  CHECK(contains(out, url(9600)));
  CHECK(contains(out, "no robot responding"));
  // ARIA's bound (about 6 s) plus start-up under emulation, not a hang.
  CHECK(took_ms < 15000);
  CHECK(noise_sent > 0);
  MESSAGE("noise far end: p3at_ctl gave up after " << took_ms << " ms, " << noise_sent.load() << " noise bytes sent");
}

TEST_CASE("reads that return a few bytes at a time reassemble into every packet, in order") {
  constexpr std::size_t kTrickled = 150;  // sent 7 bytes at a time with pauses
  constexpr std::size_t kBurst = 250;     // sent in one write
  FarEnd far([](hal::ByteStream& line, const std::atomic<bool>& stop) {
    std::vector<std::uint8_t> go(16);
    while (!stop) {  // the test's first byte says the port is open
      auto got = line.read_some(go, 50);
      if (!got.ok()) return;
      if (*got > 0) break;
    }
    const std::vector<std::uint8_t> trickle = frames_bytes(0, kTrickled);
    for (std::size_t at = 0; at < trickle.size() && !stop; at += 7) {
      const std::size_t n = std::min<std::size_t>(7, trickle.size() - at);
      if (!line.write_all(std::span<const std::uint8_t>(trickle.data() + at, n)).ok()) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    (void)line.write_all(frames_bytes(kTrickled, kTrickled + kBurst));
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  });
  REQUIRE_MESSAGE(far.wait_connected(), far.listen_error());
  auto line = open_line(115200);
  REQUIRE(line->write_all(std::vector<std::uint8_t>{'G'}).ok());

  arcos::PacketDecoder decoder = patient_decoder();
  std::size_t delivered = 0, mismatched = 0, reads = 0, reads_ending_mid_packet = 0, largest_read = 0;
  std::vector<std::uint8_t> buffer(4096);
  std::vector<std::uint8_t> received;
  const std::int64_t deadline = steady_ms() + 60000;
  while (delivered < kTrickled + kBurst && steady_ms() < deadline) {
    auto got = line->read_some(buffer, 200);
    REQUIRE_MESSAGE(got.ok(), (got.ok() ? "" : got.error().message));
    if (*got == 0) continue;
    ++reads;
    largest_read = std::max(largest_read, *got);
    received.insert(received.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*got));
    decoder.feed(std::span<const std::uint8_t>(buffer.data(), *got), steady_ms() * 1000,
                 [&](const arcos::Packet& p) {
                   if (!same_as_nth(p, delivered)) ++mismatched;
                   ++delivered;
                 });
    if (decoder.pending() > 0) ++reads_ending_mid_packet;
  }
  MESSAGE("reads=" << reads << " ending mid-packet=" << reads_ending_mid_packet << " largest=" << largest_read
                   << " bytes, packets=" << delivered << "; uart " << uart_counters().line);
  // Byte for byte what the far end sent, and every packet out of it.
  CHECK(received == frames_bytes(0, kTrickled + kBurst));
  CHECK(delivered == kTrickled + kBurst);
  CHECK(mismatched == 0);
  CHECK(decoder.stats().errors() == 0);
  CHECK(decoder.stats().discarded_bytes == 0);
  // The packets really did arrive in pieces: many reads stopped inside one.
  CHECK(reads > kTrickled);
  CHECK(reads_ending_mid_packet > kTrickled / 2);
}

TEST_CASE("a write larger than the driver's buffer is taken in pieces and arrives whole and in order") {
  constexpr int kFrames = 3000;  // 9 bytes each: 27,000 bytes, several times the 8250's 4 KiB transmit buffer
  std::atomic<int> received{0}, out_of_order{0}, tcp_reads{0};
  std::atomic<std::uint64_t> errors{0};
  std::vector<std::uint8_t> arrived;  // written by the far end's thread, read after stop()
  FarEnd far([&](hal::ByteStream& line, const std::atomic<bool>& stop) {
    arcos::PacketDecoder decoder = patient_decoder();
    std::vector<std::uint8_t> in(4096);
    while (!stop && received < kFrames) {
      auto got = line.read_some(in, 50);
      if (!got.ok()) return;
      if (*got == 0) continue;
      ++tcp_reads;
      arrived.insert(arrived.end(), in.begin(), in.begin() + static_cast<std::ptrdiff_t>(*got));
      decoder.feed(std::span<const std::uint8_t>(in.data(), *got), steady_ms() * 1000, [&](const arcos::Packet& p) {
        const auto cmd = arcos::decode_command(p);
        if (cmd.number != static_cast<std::uint8_t>(arcos::Command::vel) || cmd.value != received % 2000 - 1000) {
          ++out_of_order;
        }
        ++received;
      });
      errors = decoder.stats().errors() + decoder.stats().discarded_bytes;
    }
  });
  REQUIRE_MESSAGE(far.wait_connected(), far.listen_error());
  auto line = open_line(57600);
  std::vector<std::uint8_t> bytes;
  for (int i = 0; i < kFrames; ++i) {
    const auto f = arcos::encode_command(arcos::Command::vel, i % 2000 - 1000);
    bytes.insert(bytes.end(), f.bytes.begin(), f.bytes.begin() + static_cast<std::ptrdiff_t>(f.size));
  }
  REQUIRE(bytes.size() > 4 * 4096);
  const UartCounters before = uart_counters();
  const auto st = line->write_all(bytes);
  REQUIRE_MESSAGE(st.ok(), (st.ok() ? "" : st.error().message));
  const std::int64_t deadline = steady_ms() + 60000;
  while (received < kFrames && steady_ms() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  far.stop();
  MESSAGE("far end: " << received.load() << " frames in " << tcp_reads.load() << " reads; uart "
                       << uart_counters().line);
  CHECK(arrived == bytes);
  CHECK(received == kFrames);
  CHECK(out_of_order == 0);
  CHECK(errors == 0);
  CHECK(uart_counters().tx - before.tx >= static_cast<long long>(bytes.size()));
}
