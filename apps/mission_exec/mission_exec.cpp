// mission_exec: runs one robot's part of a mission (docs/executive.md) behind
// the launch gate (docs/launch-gate.md).
//   mission_exec --robot robot1 --mission M.yaml [--models models.yaml] --team-key team.key
// The flags and the signals; the run is the launch gate's run_mission().
// Exit statuses: p3at/launch_gate/exit_codes.hpp.

// CLI11's inline helpers trip a GCC 12 false positive (-Wnull-dereference in
// std::vector<std::string>::emplace_back inside CLI::detail::split); the
// standard headers are first included here, so this silences only them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <string>

#include "p3at/common/cli_exit.hpp"
#include "p3at/common/log.hpp"
#include "p3at/launch_gate/exit_codes.hpp"
#include "p3at/launch_gate/mission_run.hpp"

namespace {

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_signal(int) { g_stop.store(true); }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  // A closed terminal or ssh session: stop like SIGTERM (abort sent, summary
  // printed) rather than die silently with 129 while the teammates wait.
  sigaction(SIGHUP, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // a vanished peer is an error value, not a fatal signal
}

p3at::log::Level parse_level(const std::string& name) {
  if (name == "debug") return p3at::log::Level::debug;
  if (name == "warn") return p3at::log::Level::warn;
  if (name == "error") return p3at::log::Level::error;
  return p3at::log::Level::info;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{std::string(
      "mission_exec: run one robot's part of a mission (its FSA) at 10 Hz, paced by the robot's SIPs, behind the\n"
      "launch gate: the mission is verified first (as `vipars gate` does), the verdict is published on the team\n"
      "link with the mission's content hash, and the robot moves only once every robot of the mission has\n"
      "published GO for the same hash. Talks to the robot's firmware over ARCOS (--hal, default the mission\n"
      "file's) and to teammates over LCM (--lcm, default the mission file's), authenticated with the team key.\n") +
               p3at::mission_exec::kExitHelp};
  p3at::gate::MissionRunOptions opt;
  std::string log_level = "info";
  app.add_option("--robot", opt.robot, "This robot's name in the mission")->required();
  app.add_option("--mission", opt.check.mission_path, "Mission file (YAML, docs/mission-format.md)")->required();
  app.add_option("--models", opt.check.models_path,
                 "Robot models file (docs/verifier.md); default: models.yaml beside the mission file. "
                 "Without models the gate cannot run: exit 7");
  app.add_option("--tmax", opt.check.options.tmax_s, "Override the mission's Tmax (seconds), as `vipars verify --tmax`")
      ->check(CLI::PositiveNumber);
  app.add_option("--rmax", opt.check.options.rmax_m, "Override the mission's Rmax (metres)")->check(CLI::PositiveNumber);
  app.add_option("--threshold", opt.check.options.threshold, "Override the mission's launch threshold P")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--criterion", opt.check.criteria_files, "Extra criterion file (PARS, docs/verifier.md); repeatable");
  app.add_option("--gate-timeout", opt.gate_timeout_s,
                 "Seconds to wait for every teammate's verdict before refusing (default 30)")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_flag("--override-gate", opt.override_gate,
               "Operator override: vote OVERRIDE (launch) whatever this robot's verifier says; logged and published "
               "as OVERRIDE. A teammate's NO-GO, a hash mismatch or a silent teammate still refuse");
  app.add_flag("--accept-unvouched", opt.check.accept_unvouched,
               "Operator's decision: launch a mission whose probabilities say GO although the model does not vouch "
               "for one of its approximations (docs/verifier.md); without it such a mission is refused with exit 7, "
               "before it is even evaluated when the mission file shows the approximation. Logged, and published as "
               "OVERRIDE");
  app.add_option("--hal", opt.hal_url, "Robot URL: tcp://127.0.0.1:8101 or serial:///dev/ttyS0?baud=9600");
  app.add_option("--lcm", opt.lcm_url, "Team link LCM URL, e.g. udpm://239.255.76.67:7667?ttl=1");
  app.add_option("--team-key", opt.team_key_file, "Team key file (else $P3AT_TEAM_KEY names it)");
  app.add_option("--can", opt.can_url,
                 "CAN accessory bus (gyro, safety node), e.g. socketcan://can0 (docs/can-bus.md); default none");
  app.add_option("--seed", opt.seed, "Run seed for the NOISE schema (default 0)");
  app.add_option("--log-level", log_level, "debug, info, warn or error (stderr)")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));
  app.add_option("--linger-s", opt.linger_s,
                 "After finishing, keep answering teammates for up to this long (mission time), until all are done "
                 "(default 5)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--telemetry-every", opt.telemetry_every, "Publish telemetry every N cycles; 0 = never (default 1)");
  app.add_option("--teammate-silence-s", opt.teammate_silence_s,
                 "During the mission, a teammate silent this long (wall seconds) is reported and the mission's "
                 "abort_action taken (default 3)")
      ->check(CLI::Range(0.2, 3600.0));
  app.add_option("--overtime-s", opt.overtime_s,
                 "Abort, saying so, when still running this long past Tmax (mission seconds); 0 = never (default 30)")
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option("--stall-abort-ms", opt.stall_abort_ms,
                 "A stall of this process longer than this aborts the mission (the firmware watchdog, default "
                 "2000); 0 = never")
      ->check(CLI::Range(0, 3'600'000));
  app.add_flag("--resume-after-stall", opt.resume_after_stall,
               "After a stall longer than --stall-abort-ms, go on (saying so) instead of aborting");
  P3AT_CLI_PARSE(app, argc, argv);
  p3at::log::threshold() = parse_level(log_level);
  opt.team_key_env = std::getenv("P3AT_TEAM_KEY");
  return p3at::gate::run_mission(opt, g_stop, install_signal_handlers);
}
