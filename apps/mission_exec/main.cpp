// mission_exec: runs one robot's part of a mission (docs/executive.md) behind
// the launch gate (docs/launch-gate.md).
//   mission_exec --robot robot1 --mission M.yaml [--models models.yaml] --team-key team.key
// 1. Verifies the mission against the robot models and its criteria (the
//    pre-launch check, the same as `vipars gate`), before anything else.
// 2. Connects to the robot's firmware over ARCOS (serial or TCP) and joins
//    the team link over LCM.
// 3. The launch gate: publishes its verdict with the mission's content hash
//    and waits until every robot of the mission has published GO for the same
//    hash; a NO-GO, a different hash or a silent teammate means no motion.
// 4. Runs the robot's FSA at 10 Hz, paced by the robot's SIPs, re-verifying
//    from where the team is at each FSA transition.
// Exit statuses: exit_codes.hpp.

// CLI11's inline helpers trip a GCC 12 false positive (-Wnull-dereference in
// std::vector<std::string>::emplace_back inside CLI::detail::split); the
// standard headers are first included here, so this silences only them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "exit_codes.hpp"
#include "p3at/bridge/accessories/accessory_hub.hpp"
#include "p3at/bridge/accessories/guarded_drive_base.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/common/log.hpp"
#include "p3at/executive/realtime_loop.hpp"
#include "p3at/executive/robot_executive.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/can_bus.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/url.hpp"
#include "p3at/launch_gate/check_report.hpp"
#include "p3at/launch_gate/controller_clock.hpp"
#include "p3at/launch_gate/gate_session.hpp"
#include "p3at/launch_gate/gate_team_link.hpp"
#include "p3at/launch_gate/in_mission_monitor.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"
#include "p3at/launch_gate/reverifier.hpp"
#include "setup.hpp"

namespace {

using namespace p3at::mission_exec;
namespace gate = p3at::gate;

constexpr const char* kLog = "mission_exec";

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
/// t_s is mission time (the controller's clock); p_gate the launch verdict's
/// probability, p_now the latest re-verified one.
void print_summary(const p3at::exec::RobotExecutive& exec, double p_gate, const gate::InMissionMonitor& monitor) {
  const auto& o = exec.outcome();
  const auto& s = exec.stats();
  std::string reason;
  if (!o.reason.empty()) reason = " reason=\"" + o.reason + "\"";
  const double p_now = monitor.latest_p().value_or(p_gate);
  std::printf("event=finished robot=%s outcome=%s t_s=%.3f x_m=%.3f y_m=%.3f state=%s cycles=%llu overruns=%llu "
              "missed=%llu p50_us=%.1f p99_us=%.1f p_gate=%.4f p_now=%.4f reverifications=%llu "
              "reverify_max_ms=%.2f%s\n",
              exec.robot().name.c_str(), p3at::exec::to_string(o.phase), exec.elapsed_s(), exec.pose().x_m,
              exec.pose().y_m, exec.state_name().c_str(), static_cast<unsigned long long>(s.cycles()),
              static_cast<unsigned long long>(s.overruns()), static_cast<unsigned long long>(s.missed_updates()),
              s.p50_us(), s.p99_us(), p_gate, p_now, static_cast<unsigned long long>(monitor.answers()),
              monitor.max_compute_ms(), reason.c_str());
  std::fflush(stdout);
}

/// What the team link accepted and rejected, for scripts and for the record.
void print_team_link_stats(const std::string& robot, const p3at::hal::TeamLinkStats& t) {
  std::printf("event=team-link robot=%s sent=%llu retransmissions=%llu accepted=%llu acks_received=%llu "
              "rejected_unknown_sender=%llu rejected_bad_tag=%llu rejected_replay=%llu rejected_other_mission=%llu "
              "malformed=%llu verdicts_accepted=%llu telemetry_accepted=%llu\n",
              robot.c_str(), static_cast<unsigned long long>(t.sent),
              static_cast<unsigned long long>(t.retransmissions), static_cast<unsigned long long>(t.accepted),
              static_cast<unsigned long long>(t.acks_received),
              static_cast<unsigned long long>(t.rejected_unknown_sender),
              static_cast<unsigned long long>(t.rejected_bad_tag), static_cast<unsigned long long>(t.rejected_replay),
              static_cast<unsigned long long>(t.rejected_other_mission), static_cast<unsigned long long>(t.malformed),
              static_cast<unsigned long long>(t.verdicts_accepted),
              static_cast<unsigned long long>(t.telemetry_accepted));
  std::fflush(stdout);
}

int refusal_status(gate::AgreementState state) {
  switch (state) {
    case gate::AgreementState::no_go: return kExitGateNoGo;
    case gate::AgreementState::mismatch: return kExitGateMismatch;
    case gate::AgreementState::silent: return kExitGateSilent;
    case gate::AgreementState::waiting:
    case gate::AgreementState::launch: break;
  }
  return kExitAborted;
}

struct Options {
  std::string robot;
  std::string mission_file;
  std::optional<std::string> models_file;
  std::optional<std::string> hal_url;
  std::optional<std::string> lcm_url;
  std::optional<std::string> team_key_file;
  std::optional<std::string> can_url;
  std::optional<double> tmax_s;
  std::optional<double> rmax_m;
  std::optional<double> threshold;
  std::vector<std::string> criteria_files;
  double gate_timeout_s = 30.0;
  bool override_gate = false;
  bool accept_unvouched = false;
  std::uint64_t seed = 0;
  std::string log_level = "info";
  double linger_s = 5.0;
  std::uint32_t telemetry_every = 1;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{std::string(
      "mission_exec: run one robot's part of a mission (its FSA) at 10 Hz, paced by the robot's SIPs, behind the\n"
      "launch gate: the mission is verified first (as `vipars gate` does), the verdict is published on the team\n"
      "link with the mission's content hash, and the robot moves only once every robot of the mission has\n"
      "published GO for the same hash. Talks to the robot's firmware over ARCOS (--hal, default the mission\n"
      "file's) and to teammates over LCM (--lcm, default the mission file's), authenticated with the team key.\n") +
               kExitHelp};
  Options opt;
  app.add_option("--robot", opt.robot, "This robot's name in the mission")->required();
  app.add_option("--mission", opt.mission_file, "Mission file (YAML, docs/mission-format.md)")->required();
  app.add_option("--models", opt.models_file,
                 "Robot models file (docs/verifier.md); default: models.yaml beside the mission file. "
                 "Without models the gate cannot run: exit 7");
  app.add_option("--tmax", opt.tmax_s, "Override the mission's Tmax (seconds), as `vipars verify --tmax`")
      ->check(CLI::PositiveNumber);
  app.add_option("--rmax", opt.rmax_m, "Override the mission's Rmax (metres)")->check(CLI::PositiveNumber);
  app.add_option("--threshold", opt.threshold, "Override the mission's launch threshold P")->check(CLI::Range(0.0, 1.0));
  app.add_option("--criterion", opt.criteria_files, "Extra criterion file (PARS, docs/verifier.md); repeatable");
  app.add_option("--gate-timeout", opt.gate_timeout_s,
                 "Seconds to wait for every teammate's verdict before refusing (default 30)")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_flag("--override-gate", opt.override_gate,
               "Operator override: vote OVERRIDE (launch) whatever this robot's verifier says; logged and published "
               "as OVERRIDE. A teammate's NO-GO, a hash mismatch or a silent teammate still refuse");
  app.add_flag("--accept-unvouched", opt.accept_unvouched,
               "Operator's decision: launch a mission whose probabilities say GO although the model does not vouch "
               "for one of its approximations (docs/verifier.md); without it such a mission is refused with exit 7. "
               "Logged, and published as OVERRIDE");
  app.add_option("--hal", opt.hal_url, "Robot URL: tcp://127.0.0.1:8101 or serial:///dev/ttyS0?baud=9600");
  app.add_option("--lcm", opt.lcm_url, "Team link LCM URL, e.g. udpm://239.255.76.67:7667?ttl=1");
  app.add_option("--team-key", opt.team_key_file, "Team key file (else $P3AT_TEAM_KEY names it)");
  app.add_option("--can", opt.can_url,
                 "CAN accessory bus (gyro, safety node), e.g. socketcan://can0 (docs/can-bus.md); default none");
  app.add_option("--seed", opt.seed, "Run seed for the NOISE schema (default 0)");
  app.add_option("--log-level", opt.log_level, "debug, info, warn or error (stderr)")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));
  app.add_option("--linger-s", opt.linger_s,
                 "After finishing, keep answering teammates for up to this long (mission time), until all are done "
                 "(default 5)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--telemetry-every", opt.telemetry_every, "Publish telemetry every N cycles; 0 = never (default 1)");
  CLI11_PARSE(app, argc, argv);
  p3at::log::threshold() = parse_level(opt.log_level);

  // ---- configuration: any failure here is bad input (exit 2)
  const auto key = load_key(opt.team_key_file, std::getenv("P3AT_TEAM_KEY"));
  if (!key) return bad_input(key.error().message);

  // ---- the pre-launch check, before anything else: load, hash, verify
  gate::CheckRequest request;
  request.mission_path = opt.mission_file;
  request.models_path = opt.models_file;
  request.options.tmax_s = opt.tmax_s;
  request.options.rmax_m = opt.rmax_m;
  request.options.threshold = opt.threshold;
  request.criteria_files = opt.criteria_files;
  // --override-gate overrides every verifier decision, this one included.
  request.accept_unvouched = opt.accept_unvouched || opt.override_gate;
  const gate::CheckReport report = gate::pre_launch_check(request, gate::verifier_source());
  p3at::log::info(kLog, "event=gate-check robot=" + opt.robot + " " + gate::check_fields(report));
  if (report.status == gate::CheckStatus::bad_input) return bad_input(report.error);
  if (!report.verified()) {
    std::fputs(gate::format_check(report).c_str(), stdout);
    std::printf("event=gate-refused robot=%s why=%s reason=\"%s\"\n", opt.robot.c_str(), gate::to_string(report.status),
                report.error.c_str());
    std::fflush(stdout);
    return kExitGateCannotRun;
  }
  const p3at::mission::Mission& mission = *report.mission;

  const auto robot_index = find_robot(mission, opt.robot);
  if (!robot_index) return bad_input(robot_index.error().message);
  const p3at::mission::RobotSpec& spec = mission.robots[*robot_index];
  const std::string hal_url = opt.hal_url.value_or(spec.hal_url);
  if (hal_url.empty()) return bad_input("robot '" + spec.name + "' has no hal URL in the mission: pass --hal URL");
  const auto parsed_hal = p3at::hal::parse_url(hal_url);
  if (!parsed_hal) return bad_input("--hal: " + parsed_hal.error().message);
  const std::string lcm_url = opt.lcm_url.value_or(spec.lcm_url);
  std::vector<std::string> roster;
  for (const p3at::mission::RobotSpec& r : mission.robots) roster.push_back(r.name);

  // ---- the team link: LCM, authenticated with the team key; the executive
  // gets it through the gate's wrapper (wall time, verdict republishing,
  // re-verified probability in status)
  p3at::hal::SteadyClock clock;
  auto team_link = open_team_link(mission, *robot_index, lcm_url, *key);
  if (!team_link) {
    std::fprintf(stderr, "mission_exec: cannot open the team link: %s\n", team_link.error().message.c_str());
    return kExitAborted;
  }
  p3at::hal::TeamLink& inner_link = **team_link;
  gate::GateTeamLink link(inner_link, clock);

  // ---- the drive base: the ARCOS client on serial or TCP
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
      p3at::log::warn(kLog, "event=nmt-start-failed error=\"" + st.error().message + "\"");
    }
    guarded.emplace(robot, *hub, clock, [&robot] { return robot.enable_motors(true); });
  }
  p3at::hal::DriveBase& base = guarded ? static_cast<p3at::hal::DriveBase&>(*guarded) : robot;
  // Mission time is the controller's: SIPs × 100 ms (docs/launch-gate.md).
  gate::ControllerClock mission_clock(base, clock);

  // ---- in-mission re-verification, on its own thread
  gate::Reverifier reverifier(mission, *report.models, request.options, request.criteria_files,
                              gate::verifier_source());
  gate::InMissionMonitor monitor(mission, *robot_index, mission.criteria, reverifier, link);

  p3at::hal::GateVerdict own = gate::make_verdict(report, opt.override_gate);
  own.robot = spec.name;

  p3at::exec::ExecutiveOptions exec_options;
  exec_options.seed = opt.seed;
  exec_options.telemetry_every_cycles = opt.telemetry_every;
  exec_options.p_success = own.p_joint;
  exec_options.on_transition = [&monitor](const p3at::exec::TransitionEvent& e) { monitor.on_transition(e); };
  std::optional<p3at::exec::RobotExecutive> exec;
  try {
    exec.emplace(mission, *robot_index, base, link, mission_clock, exec_options);
  } catch (const std::exception& e) {
    return bad_input(e.what());
  }
  monitor.attach(*exec);

  install_signal_handlers();
  if (opt.override_gate) {
    p3at::log::warn(kLog, "event=gate-override robot=" + spec.name + " verifier_decision=" +
                              (report.result.go ? (report.result.evaluable ? "GO" : "CANNOT-EVALUATE") : "NO-GO") +
                              " p_joint=" + gate::fixed(own.p_joint, 4) + " threshold=" + gate::fixed(own.threshold, 4) +
                              " operator=--override-gate");
  } else if (report.accepted_unvouched) {
    p3at::log::warn(kLog, "event=gate-accept-unvouched robot=" + spec.name + " unvouched=" +
                              p3at::verifier::unvouched_kinds(report.result.approximations) +
                              " p_joint=" + gate::fixed(own.p_joint, 4) + " threshold=" + gate::fixed(own.threshold, 4) +
                              " operator=--accept-unvouched");
  }

  // A robot whose own verdict is NO-GO never even connects: it only tells the team.
  bool connected = false;
  if (own.decision != p3at::hal::GateDecision::no_go) {
    p3at::log::info(kLog, "event=connecting robot=" + spec.name + " hal=" + hal_url + " lcm=" + lcm_url +
                              " mission=" + mission.name + " seed=" + std::to_string(opt.seed));
    if (const auto st = robot.connect(); !st) {
      exec->abort("cannot connect to " + hal_url + ": " + st.error().message);
      print_summary(*exec, own.p_joint, monitor);
      return kExitAborted;
    }
    connected = true;
    if (guarded) {
      // Motion only once the safety node reports clear and the latch is armed.
      for (int i = 0; i < 20 && !guarded->verdict().clear; ++i) (void)guarded->wait_for_update(200);
      if (const auto st = guarded->rearm(); !st) {
        exec->abort("safety node not clear: " + st.error().message);
        print_summary(*exec, own.p_joint, monitor);
        (void)robot.disconnect();
        return kExitAborted;
      }
    }
  }

  // ---- the launch gate: nothing moves until the whole team agrees
  gate::SessionOptions session_options;
  session_options.timeout_us = static_cast<std::int64_t>(opt.gate_timeout_s * 1e6);
  const auto pace = [&](std::int64_t deadline_us) {
    // While waiting, the robot's SIPs keep its connection (and watchdog) alive.
    const std::int64_t left_us = deadline_us - clock.now_us();
    if (left_us <= 0) return;
    if (connected) {
      const auto waited = base.wait_for_update(static_cast<int>(std::max<std::int64_t>(1, left_us / 1000)));
      if (waited.ok() && waited.value()) return;
    }
    clock.sleep_until_us(deadline_us);
  };
  gate::SessionResult session = gate::run_gate_session(inner_link, clock, own, roster, session_options, pace, &g_stop);
  link.hand_over(std::move(session.early));
  const gate::Agreement& agreement = session.agreement;
  p3at::log::info(kLog, "event=gate-decision robot=" + spec.name + " state=" + gate::to_string(agreement.state) +
                            " waited_s=" + gate::fixed(static_cast<double>(session.waited_us) / 1e6, 2) +
                            " verdicts_published=" + std::to_string(session.verdicts_published) + " reason=\"" +
                            agreement.reason + "\"");
  if (session.interrupted) {
    exec->abort("interrupted by signal during the launch gate");
    if (connected) (void)robot.disconnect();
    print_summary(*exec, own.p_joint, monitor);
    print_team_link_stats(spec.name, inner_link.stats());
    return kExitAborted;
  }
  if (agreement.state != gate::AgreementState::launch) {
    if (connected) (void)robot.disconnect();
    std::fputs(gate::format_check(report).c_str(), stdout);
    std::printf("event=gate-refused robot=%s why=%s p_joint=%.4f threshold=%.4f reason=\"%s\"\n", spec.name.c_str(),
                gate::to_string(agreement.state), own.p_joint, own.threshold, agreement.reason.c_str());
    print_team_link_stats(spec.name, inner_link.stats());
    return refusal_status(agreement.state);
  }
  p3at::log::info(kLog, "event=launch robot=" + spec.name + " decision=" + p3at::hal::to_string(own.decision) +
                            " p_joint=" + gate::fixed(own.p_joint, 4) + " reason=\"" + agreement.reason + "\"");
  // Teammates still at their gate hear this robot's verdict from the mission's link.
  link.keep_publishing(own, 500'000);

  // ---- the mission
  p3at::exec::RealtimeOptions loop_options;
  loop_options.linger_ms = static_cast<std::int64_t>(opt.linger_s * 1000.0);
  loop_options.interrupt_reason = "interrupted by signal";
  // Below the abort threshold with stop_and_notify, the monitor asks for the
  // abort: the loop then aborts with that reason (its status tells the team).
  link.after_poll = [&] {
    if (auto reason = monitor.on_poll()) {
      loop_options.interrupt_reason = *reason;
      g_stop.store(true);
    }
  };
  const p3at::exec::Outcome outcome = p3at::exec::run_realtime(*exec, base, g_stop, loop_options);
  link.after_poll = nullptr;
  // The re-verification of the last transition may still be running: log and
  // publish it too (the mission is over, so it can no longer abort anything).
  reverifier.drain();
  (void)monitor.on_poll();

  // Status is best effort (UDP): repeat the final one so teammates hear it.
  for (int i = 0; i < 2; ++i) {
    clock.sleep_until_us(clock.now_us() + 50'000);
    exec->publish_status();
  }
  if (const auto st = robot.disconnect(); !st) {
    p3at::log::warn(kLog, "event=disconnect-failed error=\"" + st.error().message + "\"");
  }
  print_summary(*exec, own.p_joint, monitor);
  print_team_link_stats(spec.name, inner_link.stats());
  return outcome.phase == p3at::exec::Phase::finished ? kExitOk : kExitAborted;
}
