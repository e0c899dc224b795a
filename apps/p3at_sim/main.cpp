// p3at_sim: the simulator / firmware emulator. The composition root that puts
// the simulated world behind real TCP listeners: one ARCOS firmware per robot,
// single-threaded, stepping the world every 100 ms of simulated time, paced at
// 100 ms / speedup of wall time. See docs/simulator.md.

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/tcp_listener.hpp"
#include "p3at/sim/firmware_emulator.hpp"
#include "p3at/sim/truth_csv.hpp"
#include "p3at/sim/world.hpp"
#include "p3at/sim/world_config.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_signal(int sig) { g_stop = sig; }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  // A client vanishing mid-write must be an error value, not a fatal signal.
  std::signal(SIGPIPE, SIG_IGN);
}

void log_line(const std::string& line) { std::fprintf(stderr, "[p3at_sim] %s\n", line.c_str()); }

struct Options {
  std::string world_file;
  std::optional<int> first_port;
  double speedup = 1.0;
  std::optional<std::uint64_t> seed;
  std::string truth_csv;
  std::string host = "127.0.0.1";
  int watchdog_ms = 2000;
  int drop_opens = 0;    // fault injection: OPENs each robot ignores at first
  int drop_enables = 0;  // fault injection: ENABLE 1s each robot ignores at first
  int drop_disables = 0; // fault injection: ENABLE 0s each robot ignores at first
};

constexpr int kDefaultFirstPort = 8101;
constexpr std::int64_t kPollSliceUs = 1000;
constexpr std::int64_t kOverrunLogEveryUs = 5'000'000;

// Port of each robot: --port overrides the file (robot i on FIRST_PORT + i);
// otherwise the file's port, or 8101 + i.
std::vector<int> assign_ports(const p3at::sim::WorldConfig& world, const Options& opt) {
  std::vector<int> ports;
  std::set<int> used;
  for (std::size_t i = 0; i < world.robots.size(); ++i) {
    const int index = static_cast<int>(i);
    int port = opt.first_port ? *opt.first_port + index
                              : (world.robots[i].port >= 0 ? world.robots[i].port : kDefaultFirstPort + index);
    if (port > 65535) throw std::runtime_error("robot " + world.robots[i].name + ": port " + std::to_string(port) + " is over 65535");
    if (!used.insert(port).second) {
      throw std::runtime_error("robot " + world.robots[i].name + ": port " + std::to_string(port) +
                               " is already used by another robot (set distinct ports in the world file or use --port)");
    }
    ports.push_back(port);
  }
  return ports;
}

int run(const Options& opt) {
  p3at::sim::WorldConfig config = opt.world_file.empty() ? p3at::sim::default_world()
                                                          : p3at::sim::load_world_file(opt.world_file);
  const std::vector<int> ports = assign_ports(config, opt);
  const std::uint64_t seed = opt.seed ? *opt.seed : config.seed.value_or(1);
  p3at::sim::World world(config, seed);
  p3at::hal::SteadyClock wall;

  std::unique_ptr<p3at::sim::TruthCsvWriter> truth;
  if (!opt.truth_csv.empty()) {
    auto opened = p3at::sim::TruthCsvWriter::open(opt.truth_csv);
    if (!opened) throw std::runtime_error(opened.error().message);
    truth = std::move(opened).value();
  }

  std::vector<std::unique_ptr<p3at::hal::TcpListener>> listeners;
  std::vector<std::unique_ptr<p3at::sim::FirmwareEmulator>> firmware;
  for (std::size_t i = 0; i < world.robot_count(); ++i) {
    auto listener = p3at::hal::TcpListener::listen(opt.host, ports[i]);
    if (!listener) throw std::runtime_error("robot " + world.robot(i).name() + ": " + listener.error().message);
    listeners.push_back(std::move(listener).value());
    firmware.push_back(std::make_unique<p3at::sim::FirmwareEmulator>(world, i, wall, log_line));
    firmware.back()->set_watchdog_ms(opt.watchdog_ms);
    firmware.back()->drop_first_commands(opt.drop_opens, opt.drop_enables, opt.drop_disables);
  }
  log_line("start robots=" + std::to_string(world.robot_count()) + " speedup=" + std::to_string(opt.speedup) +
           " seed=" + std::to_string(seed) + " watchdog_ms=" + std::to_string(opt.watchdog_ms) + " world=" + (opt.world_file.empty() ? "(default)" : opt.world_file));
  for (std::size_t i = 0; i < world.robot_count(); ++i) {
    const auto& r = world.robot(i).config();
    log_line("listening robot=" + r.name + " port=" + std::to_string(listeners[i]->port()) + " host=" + opt.host +
             " subclass=" + r.subclass);
  }

  const auto period_us = static_cast<std::int64_t>(static_cast<double>(p3at::sim::kCycleUs) / opt.speedup);
  std::int64_t next_cycle_us = wall.now_us() + period_us;
  std::uint64_t overruns = 0;
  std::int64_t last_overrun_log_us = 0;
  while (!g_stop) {
    for (std::size_t i = 0; i < firmware.size(); ++i) {
      if (!firmware[i]->connected()) {
        auto client = listeners[i]->accept(0);
        if (!client) {
          log_line("accept-error robot=" + world.robot(i).name() + " error=\"" + client.error().message + "\"");
        } else if (*client) {
          firmware[i]->attach(std::move(client).value());
        }
      }
      firmware[i]->poll();
    }
    const std::int64_t now_us = wall.now_us();
    if (now_us < next_cycle_us) {
      wall.sleep_until_us(std::min(next_cycle_us, now_us + kPollSliceUs));
      continue;
    }
    world.step();
    for (auto& f : firmware) f->on_cycle();
    if (truth) {
      const p3at::Status st = truth->write_cycle(world);
      if (!st) throw std::runtime_error(st.error().message);
    }
    next_cycle_us += period_us;
    if (now_us - next_cycle_us > period_us) {
      // Too slow for this speed-up: skip ahead instead of bursting, and say so.
      const std::int64_t behind = (now_us - next_cycle_us) / period_us;
      overruns += static_cast<std::uint64_t>(behind);
      next_cycle_us = now_us + period_us;
      if (now_us - last_overrun_log_us >= kOverrunLogEveryUs) {
        log_line("overrun cycles_skipped_total=" + std::to_string(overruns));
        last_overrun_log_us = now_us;
      }
    }
  }
  log_line("stop signal=" + std::to_string(static_cast<int>(g_stop)) + " sim_time_s=" + std::to_string(static_cast<double>(world.time_us()) / 1e6) +
           " overruns=" + std::to_string(overruns));
  for (auto& f : firmware) log_line("stats robot=" + f->robot().name() + " " + p3at::sim::format_stats(f->stats()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"p3at_sim: simulated Pioneer 3-AT robots serving ARCOS firmware on TCP (like MobileSim)"};
  Options opt;
  int port = 0;
  std::uint64_t seed = 0;
  app.add_option("--world", opt.world_file, "world file (YAML, see docs/simulator.md); default: one robot, no walls");
  auto* port_opt = app.add_option("--port", port, "TCP port of the first robot, the next robots on +1, +2, ... "
                                                  "(overrides ports in the world file; default 8101)")
                       ->check(CLI::Range(1, 65535));
  app.add_option("--speedup", opt.speedup, "simulated seconds per wall-clock second (default 1)")
      ->check(CLI::Range(0.01, 1000.0));
  auto* seed_opt = app.add_option("--seed", seed, "random seed (default: the world file's, else 1)");
  app.add_option("--truth-csv", opt.truth_csv, "write true and odometric poses of every robot every cycle to FILE");
  app.add_option("--host", opt.host, "address to listen on (default 127.0.0.1)");
  app.add_option("--watchdog-ms", opt.watchdog_ms,
                 "command watchdog in simulated ms (default 2000 like ARCOS; 0 = off). At --speedup X a "
                 "client must send a command at least every watchdog/X of wall time")
      ->check(CLI::Range(0, 60000));
  app.add_option("--drop-open", opt.drop_opens,
                 "fault injection: each robot ignores the first N OPEN commands, as if the line lost them "
                 "(tests the client's resend; default 0)")
      ->check(CLI::Range(0, 1000));
  app.add_option("--drop-enable", opt.drop_enables,
                 "fault injection: each robot ignores the first N ENABLE 1 commands, sent while connecting "
                 "or later (default 0)")
      ->check(CLI::Range(0, 1000));
  app.add_option("--drop-disable", opt.drop_disables,
                 "fault injection: each robot ignores the first N ENABLE 0 commands (default 0)")
      ->check(CLI::Range(0, 1000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // bad arguments: 2, as every binary (README)
  }
  if (*port_opt) opt.first_port = port;
  if (*seed_opt) opt.seed = seed;
  install_signal_handlers();
  try {
    return run(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "p3at_sim: error: %s\n", e.what());
    return 1;
  }
}
