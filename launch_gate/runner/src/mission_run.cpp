// run_mission(): one robot's part of a mission (docs/executive.md) behind
// the launch gate (docs/launch-gate.md), the whole of mission_exec but its
// flags (apps/mission_exec):
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

#include "p3at/launch_gate/mission_run.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "p3at/launch_gate/exit_codes.hpp"
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
#include "p3at/launch_gate/launch_session.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"
#include "p3at/launch_gate/reverifier.hpp"
#include "p3at/launch_gate/teammate_watch.hpp"
#include "p3at/common/number_format.hpp"
#include "launch_setup.hpp"

namespace p3at::gate {
namespace {

using namespace p3at::mission_exec;


constexpr const char* kLog = "mission_exec";

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
              "missed=%llu stalls=%llu missed_cycles=%llu longest_stall_ms=%lld p50_us=%.1f p99_us=%.1f "
              "p_gate=%.4f p_now=%.4f reverifications=%llu reverify_max_ms=%.2f%s\n",
              exec.robot().name.c_str(), p3at::exec::to_string(o.phase), exec.elapsed_s(), exec.pose().x_m,
              exec.pose().y_m, exec.state_name().c_str(), static_cast<unsigned long long>(s.cycles()),
              static_cast<unsigned long long>(s.overruns()), static_cast<unsigned long long>(s.missed_updates()),
              static_cast<unsigned long long>(s.stalls()), static_cast<unsigned long long>(s.missed_cycles()),
              static_cast<long long>(s.longest_stall_ms()), s.p50_us(), s.p99_us(), p_gate, p_now, static_cast<unsigned long long>(monitor.answers()),
              monitor.max_compute_ms(), reason.c_str());
  std::fflush(stdout);
}

/// What the team link accepted and rejected, for scripts and for the record.
void print_team_link_stats(const std::string& robot, const p3at::hal::TeamLinkStats& t) {
  std::printf("event=team-link robot=%s sent=%llu retransmissions=%llu accepted=%llu acks_received=%llu "
              "rejected_unknown_sender=%llu rejected_bad_tag=%llu rejected_replay=%llu rejected_other_mission=%llu "
              "rejected_other_session=%llu malformed=%llu verdicts_accepted=%llu telemetry_accepted=%llu\n",
              robot.c_str(), static_cast<unsigned long long>(t.sent),
              static_cast<unsigned long long>(t.retransmissions), static_cast<unsigned long long>(t.accepted),
              static_cast<unsigned long long>(t.acks_received),
              static_cast<unsigned long long>(t.rejected_unknown_sender),
              static_cast<unsigned long long>(t.rejected_bad_tag), static_cast<unsigned long long>(t.rejected_replay),
              static_cast<unsigned long long>(t.rejected_other_mission),
              static_cast<unsigned long long>(t.rejected_other_session), static_cast<unsigned long long>(t.malformed),
              static_cast<unsigned long long>(t.verdicts_accepted),
              static_cast<unsigned long long>(t.telemetry_accepted));
  std::fflush(stdout);
}

int refusal_status(gate::AgreementState state) {
  switch (state) {
    case gate::AgreementState::no_go: return kExitGateNoGo;
    case gate::AgreementState::mismatch: return kExitGateMismatch;
    case gate::AgreementState::silent: return kExitGateSilent;
    case gate::AgreementState::in_doubt: return kExitGateInDoubt;
    case gate::AgreementState::waiting:
    case gate::AgreementState::launch: break;
  }
  return kExitAborted;
}

}  // namespace

int run_mission(const MissionRunOptions& opt, std::atomic<bool>& g_stop, const std::function<void()>& arm_signals) {
  // ---- configuration: any failure here is bad input (exit 2)
  const auto key = load_key(opt.team_key_file, opt.team_key_env);
  if (!key) return bad_input(key.error().message);

  // ---- the pre-launch check, before anything else: load, hash, verify
  gate::CheckRequest request = opt.check;
  // --override-gate overrides every verifier decision, cannot-evaluate included.
  request.accept_unvouched = opt.check.accept_unvouched || opt.override_gate;
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
    // A malformed URL is bad input (2); a well-formed one that cannot be opened is not.
    if (team_link.error().code == p3at::Error::Code::invalid_argument) {
      return bad_input("--lcm: " + team_link.error().message);
    }
    std::fprintf(stderr, "mission_exec: cannot open the team link: %s\n", team_link.error().message.c_str());
    return kExitAborted;
  }
  gate::VerdictLink& inner_link = **team_link;
  gate::GateTeamLink link(inner_link, clock);

  // ---- the drive base: the ARCOS client on serial or TCP
  p3at::bridge::ClientConfig client_config;
  client_config.serial_preamble = parsed_hal->scheme == "serial";
  client_config.auto_reconnect = false;  // a lost link aborts the mission; never reconnect mid-mission
  client_config.log_name = "bridge";
  // The executive asks for its motion every cycle: after a stall, the bridge
  // must not keep repeating a stale one from the backlog of SIPs (executive.md).
  client_config.motion_stale_sips = 10;
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

  p3at::gate::GateVerdict own = gate::make_verdict(report, opt.override_gate);
  own.robot = spec.name;
  own.nonce = gate::fresh_gate_nonce();  // this run's, never reused: binds the launch to it

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

  if (arm_signals) arm_signals();
  if (opt.override_gate) {
    p3at::log::warn(kLog, "event=gate-override robot=" + spec.name + " verifier_decision=" +
                              (report.result.go ? (report.result.evaluable ? "GO" : "CANNOT-EVALUATE") : "NO-GO") +
                              " p_joint=" + format_fixed(own.p_joint, 4) + " threshold=" + format_fixed(own.threshold, 4) +
                              " operator=--override-gate");
  } else if (report.accepted_unvouched) {
    p3at::log::warn(kLog, "event=gate-accept-unvouched robot=" + spec.name + " unvouched=" +
                              p3at::verifier::unvouched_kinds(report.result.approximations) +
                              " p_joint=" + format_fixed(own.p_joint, 4) + " threshold=" + format_fixed(own.threshold, 4) +
                              " operator=--accept-unvouched");
  }

  // A robot whose own verdict is NO-GO never even connects: it only tells the team.
  bool connected = false;
  if (own.decision != p3at::gate::GateDecision::no_go) {
    p3at::log::info(kLog, "event=connecting robot=" + spec.name + " hal=" + hal_url + " lcm=" + lcm_url +
                              " mission=" + mission.name + " seed=" + std::to_string(opt.seed));
    if (const auto st = robot.connect(); !st) {
      if (st.error().code == p3at::Error::Code::invalid_argument) return bad_input("--hal: " + st.error().message);
      exec->abort("cannot connect to " + hal_url + ": " + st.error().message);
      print_summary(*exec, own.p_joint, monitor);
      return kExitAborted;
    }
    connected = true;
    if (guarded) {
      // Motion only once the safety node reports clear and the latch is armed.
      for (int i = 0; i < 20 && !guarded->verdict().clear; ++i) (void)guarded->wait_for_update(200);
      if (const auto st = guarded->rearm(); !st) {
        // The safety node not clear ("cannot re-arm: …"), or the motors not enabled.
        exec->abort("cannot arm the robot: " + st.error().message);
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
                            " waited_s=" + format_fixed(static_cast<double>(session.waited_us) / 1e6, 2) +
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
    // In doubt is not a refusal: this robot committed, and a teammate may be moving.
    std::printf("event=%s robot=%s why=%s p_joint=%.4f threshold=%.4f reason=\"%s\"\n",
                agreement.state == gate::AgreementState::in_doubt ? "gate-in-doubt" : "gate-refused", spec.name.c_str(),
                gate::to_string(agreement.state), own.p_joint, own.threshold, agreement.reason.c_str());
    print_team_link_stats(spec.name, inner_link.stats());
    return refusal_status(agreement.state);
  }
  p3at::log::info(kLog, "event=launch robot=" + spec.name + " decision=" + gate::to_string(own.decision) +
                            " p_joint=" + format_fixed(own.p_joint, 4) + " reason=\"" + agreement.reason + "\"");
  // Teammates still at their gate hear this robot's verdict from the mission's link.
  // The verdict with the session this robot committed to.
  link.keep_publishing(session.published, 500'000);

  // ---- the mission
  p3at::exec::RealtimeOptions loop_options;
  loop_options.linger_ms = static_cast<std::int64_t>(opt.linger_s * 1000.0);
  loop_options.interrupt_reason = "interrupted by signal";
  loop_options.stall_abort_ms = opt.stall_abort_ms;
  loop_options.resume_after_stall = opt.resume_after_stall;
  // Teammates' liveness: every message of the session is a heartbeat.
  std::vector<std::string> teammates;
  for (const std::string& name : roster) {
    if (name != spec.name) teammates.push_back(name);
  }
  gate::TeammateWatch watch(teammates, static_cast<std::int64_t>(opt.teammate_silence_s * 1e6));
  watch.start(clock.now_us());
  const bool stop_on_fault = mission.criteria.abort_action == p3at::mission::AbortAction::stop_and_notify;
  const double overtime_at_s = mission.criteria.tmax_s + opt.overtime_s;
  bool overtime_said = false;
  const auto request_abort = [&](const std::string& reason) {
    if (g_stop.load()) return;
    loop_options.interrupt_reason = reason;
    g_stop.store(true);
  };
  // Below the abort threshold with stop_and_notify, the monitor asks for the
  // abort: the loop then aborts with that reason (its status tells the team).
  link.after_poll = [&] {
    if (auto reason = monitor.on_poll()) request_abort(*reason);
    for (const gate::SilentTeammate& t : watch.check(clock.now_us(), inner_link)) {
      const std::string what = "teammate " + t.robot + " silent for " + format_fixed(t.silent_s, 1) + " s (limit " +
                               format_fixed(opt.teammate_silence_s, 1) + " s)";
      p3at::log::warn(kLog, "event=teammate-silent robot=" + spec.name + " teammate=" + t.robot + " silent_s=" +
                                format_fixed(t.silent_s, 1) + " action=" +
                                (stop_on_fault ? "stop_and_notify" : "continue_and_warn"));
      if (stop_on_fault) {
        request_abort(what);
      } else {
        link.set_note("warning: " + what + "; continuing");
      }
    }
    // Nobody waits for ever: past Tmax + the margin, say so and stop.
    if (opt.overtime_s > 0 && !overtime_said && exec->running() && exec->elapsed_s() > overtime_at_s) {
      overtime_said = true;
      const std::string what = "overtime: still running at t_s=" + format_fixed(exec->elapsed_s(), 1) +
                               ", past Tmax " + format_fixed(mission.criteria.tmax_s, 1) + " s + " +
                               format_fixed(opt.overtime_s, 1) + " s";
      p3at::log::warn(kLog, "event=overtime robot=" + spec.name + " t_s=" + format_fixed(exec->elapsed_s(), 1) +
                                " tmax_s=" + format_fixed(mission.criteria.tmax_s, 1));
      request_abort(what);
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

}  // namespace p3at::gate
