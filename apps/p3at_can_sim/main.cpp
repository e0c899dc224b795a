// p3at_can_sim: the robot's CAN accessories (yaw-rate gyro and safety node)
// simulated on a real CAN interface, for hardware-in-the-loop tests:
//   p3at_can_sim --bus socketcan://vcan0 --bias 0.01 --noise 0.002
// then type commands ("estop on", "rate 0.5", …; see --help) on stdin.

// GCC 12 reports a false "potential null pointer dereference" inside CLI11's
// split() once inlined here; CLI11 comes first so <string> is inside the pragma.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <string>

#include "p3at/common/cli_exit.hpp"
#include "p3at/sim/can/node_commands.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/sim/can/sim_accessories.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop = true; }

// Reads whatever stdin has, without blocking; complete lines go to `on_line`.
// Returns false at end of input.
template <class OnLine>
bool read_stdin_lines(std::string& buffer, OnLine on_line) {
  char chunk[512];
  const ssize_t n = ::read(STDIN_FILENO, chunk, sizeof chunk);
  if (n == 0) return false;
  if (n < 0) return errno == EINTR || errno == EAGAIN;
  buffer.append(chunk, static_cast<std::size_t>(n));
  for (std::size_t nl; (nl = buffer.find('\n')) != std::string::npos;) {
    on_line(buffer.substr(0, nl));
    buffer.erase(0, nl + 1);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"p3at_can_sim: simulated CAN accessories (yaw-rate gyro and safety node, CANopen) on a CAN\n"
               "interface, for hardware-in-the-loop tests. Frame layouts: docs/can-bus.md."};
  std::string bus_url = "socketcan://vcan0";
  p3at::sim::SimGyroConfig gyro;
  p3at::sim::SimSafetyNodeConfig safety;
  int gyro_node = gyro.node_id;
  int safety_node = safety.node_id;
  bool no_gyro = false;
  bool no_safety = false;
  bool auto_start = false;
  double yaw_rate = 0.0;
  double duration_s = 0.0;
  app.add_option("--bus", bus_url, "CAN bus URL")->capture_default_str();
  app.add_option("--gyro-node", gyro_node, "gyro node id (1-127)")->capture_default_str()->check(CLI::Range(1, 127));
  app.add_option("--safety-node", safety_node, "safety node id (1-127)")
      ->capture_default_str()
      ->check(CLI::Range(1, 127));
  app.add_flag("--no-gyro", no_gyro, "do not simulate the gyro");
  app.add_flag("--no-safety", no_safety, "do not simulate the safety node");
  app.add_option("--bias", gyro.bias_radps, "gyro bias, rad/s")->capture_default_str();
  app.add_option("--drift", gyro.bias_drift_radps_per_s, "gyro bias drift, rad/s per s")->capture_default_str();
  app.add_option("--noise", gyro.noise_sd_radps, "gyro white noise per sample, rad/s (1 sigma)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--scale", gyro.scale_error, "gyro scale error (0.01 = reads 1 % high)")->capture_default_str();
  app.add_option("--yaw-rate", yaw_rate, "initial true yaw rate, rad/s (stdin: rate RADPS)")->capture_default_str();
  app.add_option("--seed", gyro.seed, "noise seed")->capture_default_str();
  app.add_flag("--auto-start", auto_start, "nodes go operational without waiting for NMT start");
  app.add_option("--duration", duration_s, "run this many seconds, then exit (0 = until 'quit' or end of stdin)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.footer(p3at::can_sim::command_help());
  P3AT_CLI_PARSE(app, argc, argv);
  if (no_gyro && no_safety) {
    std::fprintf(stderr, "p3at_can_sim: --no-gyro and --no-safety leave nothing to simulate\n");
    return 2;
  }
  if (gyro_node == safety_node && !no_gyro && !no_safety) {
    std::fprintf(stderr, "p3at_can_sim: the gyro and the safety node need different node ids\n");
    return 2;
  }
  gyro.node_id = static_cast<std::uint8_t>(gyro_node);
  safety.node_id = static_cast<std::uint8_t>(safety_node);
  gyro.auto_start = auto_start;
  safety.auto_start = auto_start;

  auto bus = p3at::hal::open_can_bus(bus_url);
  if (!bus) {
    std::fprintf(stderr, "p3at_can_sim: %s\n", bus.error().message.c_str());
    // A malformed URL is bad input (2); a missing interface is not.
    return bus.error().code == p3at::Error::Code::invalid_argument ? 2 : 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);

  p3at::sim::SimAccessories nodes(**bus, gyro, safety, !no_gyro, !no_safety);
  p3at::hal::SteadyClock clock;
  const std::int64_t start_us = clock.now_us();
  const auto end_us = start_us + static_cast<std::int64_t>(duration_s * 1e6);
  std::printf("[p3at_can_sim] event=ready bus=%s gyro_node=%d safety_node=%d gyro=%s safety=%s\n", bus_url.c_str(),
              gyro_node, safety_node, no_gyro ? "off" : "on", no_safety ? "off" : "on");
  std::fflush(stdout);

  std::string pending;
  bool stdin_open = true;
  p3at::hal::CanBusState last_state = (*bus)->status().state;
  std::string last_send_error;
  while (!g_stop) {
    const std::int64_t now_us = clock.now_us();
    if (duration_s > 0 && now_us >= end_us) break;
    if (auto st = nodes.step(now_us, yaw_rate); !st && st.error().message != last_send_error) {
      last_send_error = st.error().message;  // once per distinct error: a bus-off repeats it every tick
      std::printf("[p3at_can_sim] event=send-failed error=\"%s\"\n", last_send_error.c_str());
    } else if (st) {
      last_send_error.clear();
    }
    if ((*bus)->status().state != last_state) {
      last_state = (*bus)->status().state;
      std::printf("[p3at_can_sim] event=bus-state state=%s\n", p3at::hal::to_string(last_state));
    }
    std::fflush(stdout);
    // Wait about a millisecond, for stdin or CAN input.
    pollfd pfd{STDIN_FILENO, POLLIN, 0};
    const int ready = stdin_open ? ::poll(&pfd, 1, 1) : (::usleep(1000), 0);
    if (ready > 0) {
      stdin_open = read_stdin_lines(pending, [&](const std::string& line) {
        auto effect = p3at::can_sim::apply_command(line, nodes);
        if (!effect) {
          std::printf("[p3at_can_sim] event=bad-command error=\"%s\"\n", effect.error().message.c_str());
          return;
        }
        if (effect->has_rate) yaw_rate = effect->rate_radps;
        if (effect->quit) g_stop = true;
        std::printf("[p3at_can_sim] event=command line=\"%s\"\n", line.c_str());
      });
      if (!stdin_open && duration_s <= 0) break;
    }
  }
  std::printf("[p3at_can_sim] event=exit gyro_samples=%llu safety_states=%llu frames_received=%llu\n",
              static_cast<unsigned long long>(nodes.gyro().samples_sent()),
              static_cast<unsigned long long>(nodes.safety().states_sent()),
              static_cast<unsigned long long>(nodes.frames_received()));
  return 0;
}
