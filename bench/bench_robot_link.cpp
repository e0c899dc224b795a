// Benchmark of the robot link (issue: foundation and the Pioneer robot link).
//  1. SIP-to-reaction latency: p3at_sim runs as a separate process on the
//     loopback, sped up so 10,000 SIPs take seconds; for each SIP the bridge
//     reads, decodes and turns it into robot state, and the bench reacts with
//     a velocity command. Latency = from the moment the read returning the SIP
//     completed to the moment the command's write completed.
//  2. Decoder throughput: a buffer of real SIPs fed through PacketDecoder +
//     decode_sip, in one chunk and in 7-byte chunks.
// Prints a table. Usage: bench_robot_link [--cycles N] [--speedup X]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/common/log.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/sip.hpp"

using namespace p3at;

namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  return v[i];
}

struct Throughput {
  double mb_per_s;
  double packets_per_s;
};

Throughput decoder_throughput(std::size_t chunk) {
  arcos::Sip sip;
  sip.sonar_count = 16;
  for (std::uint8_t i = 0; i < 16; ++i) sip.sonar[i] = {i, static_cast<std::uint16_t>(1000 + i)};
  sip.io = arcos::SipIo{};
  sip.battery_x10 = 130;
  sip.charge_state = 0;
  sip.rotvel = 10;
  sip.fault_flags = 0;
  sip.latvel = 0;
  sip.temperature = 25;
  sip.state_of_charge = 0;
  sip.controller_time_us = 123;
  sip.flags3 = 0;
  const arcos::Frame frame = arcos::encode_sip(sip);
  std::vector<std::uint8_t> buffer;
  for (int i = 0; i < 20000; ++i) buffer.insert(buffer.end(), frame.bytes.begin(), frame.bytes.begin() + frame.size);
  std::uint64_t packets = 0;
  const int repeats = 20;
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) {
    arcos::PacketDecoder decoder;
    for (std::size_t off = 0; off < buffer.size(); off += chunk) {
      const std::size_t n = std::min(chunk, buffer.size() - off);
      decoder.feed(std::span<const std::uint8_t>(buffer.data() + off, n), 0, [&](const arcos::Packet& p) {
        if (arcos::decode_sip(p).ok()) ++packets;
      });
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {static_cast<double>(buffer.size()) * repeats / secs / 1e6, static_cast<double>(packets) / secs};
}

}  // namespace

int main(int argc, char** argv) {
  int cycles = 10000;
  double speedup = 50.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--cycles") == 0) cycles = std::max(100, std::atoi(argv[i + 1]));
    if (std::strcmp(argv[i], "--speedup") == 0) speedup = std::atof(argv[i + 1]);
  }
  log::threshold() = log::Level::warn;

  const int port = test::free_tcp_port();
  test::ChildProcess sim({P3AT_SIM_BIN, "--port", std::to_string(port), "--speedup", std::to_string(speedup)},
                         test::scratch_path("bench-sim.log"));
  if (!sim.wait_for_log("port=" + std::to_string(port), 10.0)) {
    std::fprintf(stderr, "bench_robot_link: p3at_sim did not start:\n%s\n", sim.log().c_str());
    return 1;
  }
  hal::SteadyClock clock;
  const std::string url = "tcp://127.0.0.1:" + std::to_string(port);
  bridge::ArcosClient client([url] { return hal::open_byte_stream(url); }, clock);
  if (auto st = client.connect(); !st) {
    std::fprintf(stderr, "bench_robot_link: %s\n", st.error().message.c_str());
    return 1;
  }
  std::vector<double> latency_us;
  latency_us.reserve(static_cast<std::size_t>(cycles));
  int warmup = 20;
  int missed = 0;
  while (static_cast<int>(latency_us.size()) < cycles) {
    auto updated = client.wait_for_update(500);
    if (!updated || !updated.value()) {
      if (++missed > 50) break;
      continue;
    }
    // Alternate between two speeds so that every SIP causes a command to be written.
    const double v = (client.stats().sips % 2 == 0) ? 0.100 : 0.101;
    if (!client.set_velocity(v, 0.0)) break;
    const std::int64_t reacted = clock.now_us();
    if (warmup > 0) {
      --warmup;
      continue;
    }
    latency_us.push_back(static_cast<double>(reacted - client.state().stamp_us));
  }
  (void)client.stop();
  (void)client.disconnect();
  sim.signal(SIGTERM);
  (void)sim.wait_exit(5.0);

  const Throughput whole = decoder_throughput(1 << 20);
  const Throughput small = decoder_throughput(7);

  std::printf("\nrobot link benchmark (p3at_sim at %.0fx over loopback TCP, %zu cycles)\n", speedup, latency_us.size());
  std::printf("| measure                                  | value        |\n");
  std::printf("|------------------------------------------|--------------|\n");
  std::printf("| SIP read -> command written, p50         | %9.1f us |\n", percentile(latency_us, 0.50));
  std::printf("| SIP read -> command written, p99         | %9.1f us |\n", percentile(latency_us, 0.99));
  std::printf("| SIP read -> command written, max         | %9.1f us |\n", percentile(latency_us, 1.0));
  std::printf("| cycles without a SIP within 500 ms       | %12d |\n", missed);
  std::printf("| decoder + decode_sip, 1 MiB chunks       | %7.1f MB/s |\n", whole.mb_per_s);
  std::printf("| decoder + decode_sip, 1 MiB chunks       | %6.2f M pkt/s |\n", whole.packets_per_s / 1e6);
  std::printf("| decoder + decode_sip, 7-byte chunks      | %7.1f MB/s |\n", small.mb_per_s);
  std::printf("| decoder + decode_sip, 7-byte chunks      | %6.2f M pkt/s |\n", small.packets_per_s / 1e6);
  std::printf("| real-time need: one 70-byte SIP / 100 ms | %7.4f MB/s |\n", 70.0 / 0.1 / 1e6);
  return static_cast<int>(latency_us.size()) == cycles ? 0 : 1;
}
