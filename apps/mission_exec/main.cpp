// mission_exec: runs one robot's part of a mission (docs/executive.md).
//   mission_exec --robot robot1 --mission examples/relay/mission.yaml --team-key team.key
// Loads the mission, connects to the robot's firmware over ARCOS (serial or
// TCP), joins the team link over LCM, and runs the robot's FSA at 10 Hz, paced
// by the robot's SIPs. Exit: 0 finished, 2 bad input, 3 aborted (link loss,
// safety stop, teammate abort, interrupt) or could not start.

// CLI11's inline helpers trip a GCC 12 false positive (-Wnull-dereference in
// std::vector<std::string>::emplace_back inside CLI::detail::split); the
// standard headers are first included here, so this silences only them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop

#include <atomic>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "p3at/bridge/accessories/accessory_hub.hpp"
#include "p3at/bridge/accessories/guarded_drive_base.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/common/log.hpp"
#include "p3at/executive/realtime_loop.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/url.hpp"
#include "setup.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitAborted = 3;

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_signal(int) { g_stop.store(true); }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // a vanished peer is an error value, not a fatal signal
}

p3at::log::Level parse_level(const std::string& name) {
  if (name == "debug") return p3at::log::Level::debug;
  if (name == "warn") return p3at::log::Level::warn;
  if (name == "error") return p3at::log::Level::error;
  return p3at::log::Level::info;
}

int bad_input(const std::string& message) {
  std::fprintf(stderr, "mission_exec: %s\n", message.c_str());
  return kExitBadInput;
}

/// The one summary line on stdout, for scripts: `event=finished robot=.. outcome=..`.
void print_summary(const p3at::exec::RobotExecutive& exec) {
  const auto& o = exec.outcome();
  const auto& s = exec.stats();
  std::string reason;
  if (!o.reason.empty()) reason = " reason=\"" + o.reason + "\"";
  std::printf("event=finished robot=%s outcome=%s t_s=%.3f x_m=%.3f y_m=%.3f state=%s cycles=%llu overruns=%llu "
              "missed=%llu p50_us=%.1f p99_us=%.1f%s\n",
              exec.robot().name.c_str(), p3at::exec::to_string(o.phase), exec.elapsed_s(), exec.pose().x_m,
              exec.pose().y_m, exec.state_name().c_str(), static_cast<unsigned long long>(s.cycles()),
              static_cast<unsigned long long>(s.overruns()), static_cast<unsigned long long>(s.missed_updates()),
              s.p50_us(), s.p99_us(), reason.c_str());
  std::fflush(stdout);
}

/// What the team link accepted and rejected, for scripts and for the record.
void print_team_link_stats(const std::string& robot, const p3at::hal::TeamLinkStats& t) {
  std::printf("event=team-link robot=%s sent=%llu retransmissions=%llu accepted=%llu acks_received=%llu "
              "rejected_unknown_sender=%llu rejected_bad_tag=%llu rejected_replay=%llu rejected_other_mission=%llu "
              "malformed=%llu\n",
              robot.c_str(), static_cast<unsigned long long>(t.sent),
              static_cast<unsigned long long>(t.retransmissions), static_cast<unsigned long long>(t.accepted),
              static_cast<unsigned long long>(t.acks_received),
              static_cast<unsigned long long>(t.rejected_unknown_sender),
              static_cast<unsigned long long>(t.rejected_bad_tag), static_cast<unsigned long long>(t.rejected_replay),
              static_cast<unsigned long long>(t.rejected_other_mission), static_cast<unsigned long long>(t.malformed));
  std::fflush(stdout);
}

struct Options {
  std::string robot;
  std::string mission_file;
  std::optional<std::string> hal_url;
  std::optional<std::string> lcm_url;
  std::optional<std::string> team_key_file;
  std::optional<std::string> can_url;
  std::uint64_t seed = 0;
  std::string log_level = "info";
  double linger_s = 5.0;
  std::uint32_t telemetry_every = 1;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "mission_exec: run one robot's part of a mission (its FSA) at 10 Hz, paced by the robot's SIPs.\n"
      "Talks to the robot's firmware over ARCOS (--hal, default the mission file's) and to teammates over\n"
      "LCM (--lcm, default the mission file's), authenticated with the team key.\n"
      "Exit status: 0 finished, 2 bad input, 3 aborted (link loss, safety stop, teammate abort, signal)."};
  Options opt;
  app.add_option("--robot", opt.robot, "This robot's name in the mission")->required();
  app.add_option("--mission", opt.mission_file, "Mission file (YAML, docs/mission-format.md)")->required();
  app.add_option("--hal", opt.hal_url, "Robot URL: tcp://127.0.0.1:8101 or serial:///dev/ttyS0?baud=9600");
  app.add_option("--lcm", opt.lcm_url, "Team link LCM URL, e.g. udpm://239.255.76.67:7667?ttl=1");
  app.add_option("--team-key", opt.team_key_file, "Team key file (else $P3AT_TEAM_KEY names it)");
  app.add_option("--can", opt.can_url,
                 "CAN accessory bus (gyro, safety node), e.g. socketcan://can0 (docs/can-bus.md); default none");
  app.add_option("--seed", opt.seed, "Run seed for the NOISE schema (default 0)");
  app.add_option("--log-level", opt.log_level, "debug, info, warn or error (stderr)")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));
  app.add_option("--linger-s", opt.linger_s,
                 "After finishing, keep answering teammates for up to this long, until all are done (default 5)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--telemetry-every", opt.telemetry_every, "Publish telemetry every N cycles; 0 = never (default 1)");
  CLI11_PARSE(app, argc, argv);
  p3at::log::threshold() = parse_level(opt.log_level);

  // ---- configuration: any failure here is bad input (exit 2)
  auto mission = p3at::mission_exec::load_mission(opt.mission_file);
  if (!mission) return bad_input(mission.error().message);
  const auto robot_index = p3at::mission_exec::find_robot(*mission, opt.robot);
  if (!robot_index) return bad_input(robot_index.error().message);
  const p3at::mission::RobotSpec& spec = mission->robots[*robot_index];
  const std::string hal_url = opt.hal_url.value_or(spec.hal_url);
  if (hal_url.empty()) return bad_input("robot '" + spec.name + "' has no hal URL in the mission: pass --hal URL");
  const auto parsed_hal = p3at::hal::parse_url(hal_url);
  if (!parsed_hal) return bad_input("--hal: " + parsed_hal.error().message);
  const std::string lcm_url = opt.lcm_url.value_or(spec.lcm_url);
  const auto key = p3at::mission_exec::load_key(opt.team_key_file, std::getenv("P3AT_TEAM_KEY"));
  if (!key) return bad_input(key.error().message);

  // ---- the team link: LCM, authenticated with the team key
  auto team_link = p3at::mission_exec::open_team_link(*mission, *robot_index, lcm_url, *key);
  if (!team_link) {
    std::fprintf(stderr, "mission_exec: cannot open the team link: %s\n", team_link.error().message.c_str());
    return kExitAborted;
  }

  // ---- the drive base: the ARCOS client on serial or TCP
  p3at::hal::SteadyClock clock;
  p3at::bridge::ClientConfig client_config;
  client_config.serial_preamble = parsed_hal->scheme == "serial";
  client_config.auto_reconnect = false;  // a lost link aborts the mission; never reconnect mid-mission
  client_config.log_name = "bridge";
  p3at::bridge::ArcosClient robot([hal_url] { return p3at::hal::open_byte_stream(hal_url); }, clock, client_config);

  // ---- optional CAN accessories: the safety node can stop the robot within one
  // cycle and the gyro aids the heading; the executive then drives the guarded base.
  std::unique_ptr<p3at::hal::CanBus> can_bus;
  std::optional<p3at::bridge::AccessoryHub> hub;
  std::optional<p3at::bridge::GuardedDriveBase> guarded;
  if (opt.can_url) {
    auto bus = p3at::hal::open_can_bus(*opt.can_url);
    if (!bus) return bad_input("--can: " + bus.error().message);
    can_bus = std::move(bus).value();
    hub.emplace(*can_bus);
    if (const auto st = hub->start(); !st) {
      p3at::log::warn("mission_exec", "event=nmt-start-failed error=\"" + st.error().message + "\"");
    }
    guarded.emplace(robot, *hub, clock, [&robot] { return robot.enable_motors(true); });
  }
  p3at::hal::DriveBase& base = guarded ? static_cast<p3at::hal::DriveBase&>(*guarded) : robot;

  p3at::exec::ExecutiveOptions exec_options;
  exec_options.seed = opt.seed;
  exec_options.telemetry_every_cycles = opt.telemetry_every;
  std::optional<p3at::exec::RobotExecutive> exec;
  try {
    exec.emplace(*mission, *robot_index, base, **team_link, clock, exec_options);
  } catch (const std::exception& e) {
    return bad_input(e.what());
  }

  install_signal_handlers();
  p3at::log::info("mission_exec", "event=connecting robot=" + spec.name + " hal=" + hal_url + " lcm=" + lcm_url +
                                      " mission=" + mission->name + " seed=" + std::to_string(opt.seed));
  if (const auto st = robot.connect(); !st) {
    exec->abort("cannot connect to " + hal_url + ": " + st.error().message);
    print_summary(*exec);
    return kExitAborted;
  }

  if (guarded) {
    // Motion only once the safety node reports clear and the latch is armed.
    for (int i = 0; i < 20 && !guarded->verdict().clear; ++i) (void)guarded->wait_for_update(200);
    if (const auto st = guarded->rearm(); !st) {
      exec->abort("safety node not clear: " + st.error().message);
      print_summary(*exec);
      (void)robot.disconnect();
      return kExitAborted;
    }
  }

  p3at::exec::RealtimeOptions loop_options;
  loop_options.linger_ms = static_cast<std::int64_t>(opt.linger_s * 1000.0);
  loop_options.interrupt_reason = "interrupted by signal";
  const p3at::exec::Outcome outcome = p3at::exec::run_realtime(*exec, base, g_stop, loop_options);

  // Status is best effort (UDP): repeat the final one so teammates hear it.
  for (int i = 0; i < 2; ++i) {
    clock.sleep_until_us(clock.now_us() + 50'000);
    exec->publish_status();
  }
  if (const auto st = robot.disconnect(); !st) {
    p3at::log::warn("mission_exec", "event=disconnect-failed error=\"" + st.error().message + "\"");
  }
  print_summary(*exec);
  print_team_link_stats(spec.name, (*team_link)->stats());
  return outcome.phase == p3at::exec::Phase::finished ? kExitOk : kExitAborted;
}
