// p3at_ctl: a console for any Pioneer 3-AT, real (serial) or simulated (TCP).
// How an engineer checks a robot before a mission:
//   p3at_ctl tcp://127.0.0.1:8101 status
//   p3at_ctl serial:///dev/ttyUSB0?baud=9600 drive --vel 300 --secs 3
//   p3at_ctl tcp://127.0.0.1:8101 drive --square 1

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <string>

#include "drive_commands.hpp"
#include "p3at/common/cli_exit.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/common/log.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/url.hpp"

namespace {

std::atomic<bool> g_interrupted{false};

void on_signal(int) { g_interrupted = true; }

constexpr double kPi = 3.14159265358979323846;

void print_status(const p3at::bridge::ArcosClient& robot) {
  const auto& info = robot.info();
  const auto& s = robot.state();
  std::printf("robot     name=%s class=%s subclass=%s\n", info.identity.name.c_str(),
              info.identity.robot_class.c_str(), info.identity.subclass.c_str());
  if (info.config) {
    const auto& c = *info.config;
    std::printf("config    serial=%s firmware=%s sip_cycle_ms=%u watchdog_ms=%u\n", c.serial_number.c_str(),
                c.firmware_version.c_str(), c.sip_cycle_ms, c.watchdog_ms);
    std::printf("config    trans_vel_max_mm_s=%u rot_vel_max_deg_s=%u trans_accel=%u trans_decel=%u rot_accel=%u "
                "rot_decel=%u top_trans_vel=%u top_rot_vel=%u\n",
                c.trans_vel_max, c.rot_vel_max, c.trans_accel, c.trans_decel, c.rot_accel, c.rot_decel,
                c.top_trans_vel, c.top_rot_vel);
  } else {
    std::printf("config    (robot did not answer CONFIG)\n");
  }
  std::printf("params    dist_conv=%.3f vel_conv=%.3f range_conv=%.3f\n", info.params.dist_conv,
              info.params.vel_conv, info.params.range_conv);
  std::printf("battery   %.1f V\n", s.battery_v);
  std::printf("flags     0x%04x motors=%s estop=%s stall_left=%d stall_right=%d bumpers=0x%04x faults=0x%04x\n",
              s.flags, s.motors_enabled ? "enabled" : "disabled", s.estop_pressed ? "pressed" : "clear",
              s.left_stall ? 1 : 0, s.right_stall ? 1 : 0, s.bumpers, s.fault_flags);
  std::printf("pose      x_m=%.3f y_m=%.3f th_deg=%.2f (odometry since connect)\n", s.odometry.x_m,
              s.odometry.y_m, s.odometry.theta_rad * 180.0 / kPi);
  std::printf("velocity  trans_mps=%.3f rot_dps=%.2f\n", s.trans_vel_mps, s.rot_vel_radps * 180.0 / kPi);
  std::printf("sonar_m  ");
  for (int i = 0; i < p3at::hal::kSonarCount; ++i) {
    const double r = s.sonar_m[static_cast<std::size_t>(i)];
    if (r < 0) {
      std::printf(" %d:--", i);
    } else {
      std::printf(" %d:%.2f", i, r);
    }
  }
  std::printf("\n");
  const auto& d = robot.decoder_stats();
  std::printf("link      sips=%llu bad_header=%llu bad_checksum=%llu bad_count=%llu timeouts=%llu\n",
              static_cast<unsigned long long>(robot.stats().sips), static_cast<unsigned long long>(d.bad_header),
              static_cast<unsigned long long>(d.bad_checksum), static_cast<unsigned long long>(d.bad_count),
              static_cast<unsigned long long>(d.timeouts));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"p3at_ctl: connect to a Pioneer 3-AT (real or simulated) over ARCOS, print its state, drive it.\n"
               "URL is tcp://HOST:PORT (simulators, p3at_sim) or serial:///dev/ttyS0?baud=9600 (a real robot)."};
  app.require_subcommand(1);
  std::string url;
  std::string log_level = "warn";
  app.add_option("url", url, "Robot URL: tcp://127.0.0.1:8101 or serial:///dev/ttyS0?baud=9600")->required();
  app.add_option("--log-level", log_level, "debug, info, warn or error (stderr)")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));

  auto* status = app.add_subcommand("status", "Print what the robot reports, then disconnect");
  p3at::ctl::DriveOptions drive_options;
  auto* drive = app.add_subcommand("drive", "Drive and print odometry as it goes");
  auto* vel = drive->add_option("--vel", drive_options.vel_mm_s, "Translational velocity, mm/s")
                  ->check(CLI::Range(-1500.0, 1500.0));
  drive->add_option("--rotvel", drive_options.rotvel_deg_s, "Rotational velocity, deg/s (+ = counter-clockwise)")
      ->check(CLI::Range(-300.0, 300.0));
  auto* secs = drive->add_option("--secs", drive_options.secs, "How long to drive, s")->check(CLI::Range(0.0, 3600.0));
  auto* square = drive->add_option("--square", drive_options.square_m, "Drive a square with this side, m")
                     ->check(CLI::Range(0.05, 100.0));
  drive->add_option("--print-every", drive_options.print_every_s, "Seconds between odometry lines")
      ->check(CLI::Range(0.05, 60.0));
  square->excludes(secs);
  (void)vel;

  P3AT_CLI_PARSE(app, argc, argv);
  if (drive->parsed() && !square->count() && !secs->count()) {
    std::fprintf(stderr, "p3at_ctl: drive needs --secs S (with --vel/--rotvel) or --square M\n");
    return 2;
  }
  p3at::log::threshold() = log_level == "debug"  ? p3at::log::Level::debug
                           : log_level == "info" ? p3at::log::Level::info
                           : log_level == "warn" ? p3at::log::Level::warn
                                                 : p3at::log::Level::error;

  auto parsed = p3at::hal::parse_url(url);
  if (!parsed) {
    std::fprintf(stderr, "p3at_ctl: %s\n", parsed.error().message.c_str());
    return 2;
  }
  p3at::bridge::ClientConfig config;
  config.serial_preamble = parsed->scheme == "serial";
  config.auto_reconnect = false;  // a console reports a lost link rather than hiding it
  config.log_name = "p3at_ctl";
  p3at::hal::SteadyClock clock;
  p3at::bridge::ArcosClient robot([url] { return p3at::hal::open_byte_stream(url); }, clock, config);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  if (auto st = robot.connect(); !st) {
    std::fprintf(stderr, "p3at_ctl: cannot connect to %s: %s\n", url.c_str(), st.error().message.c_str());
    // A malformed URL (an unknown scheme…) is bad input, like a bad flag.
    return st.error().code == p3at::Error::Code::invalid_argument ? 2 : 1;
  }
  int rc = 0;
  if (status->parsed()) {
    // Gather a second of SIPs so every sonar has reported at least once.
    for (int i = 0; i < 10 && !g_interrupted; ++i) (void)robot.wait_for_update(250);
    print_status(robot);
    if (robot.state().link != p3at::hal::LinkState::ok) rc = 1;
  } else if (square->count()) {
    rc = p3at::ctl::drive_square(robot, clock, drive_options, g_interrupted);
  } else {
    rc = p3at::ctl::drive_constant(robot, clock, drive_options, g_interrupted);
  }
  if (g_interrupted) {
    (void)robot.stop();
    std::fprintf(stderr, "p3at_ctl: interrupted, robot stopped\n");
    rc = 130;
  }
  if (auto st = robot.disconnect(); !st && rc == 0) {
    std::fprintf(stderr, "p3at_ctl: disconnect: %s\n", st.error().message.c_str());
    rc = 1;
  }
  return rc;
}
