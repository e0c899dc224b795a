// vipars calibrate [--world FILE | --hal URL | --from-log FILE.csv] [options]
// The flags; the calibration is p3at_calibration_rig's run_calibrate().

#include <memory>

#include "commands.hpp"
#include "p3at/calibration_rig/calibrate.hpp"

namespace p3at::vipars {

void register_calibrate(CLI::App& app, int& exit_status) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Fit the robot-models file from calibration runs: simulated (--world), over ARCOS (--hal) or logged (--from-log)");
  cmd->add_option("--world", o->world_file,
                  "World file: the simulated robots and radio (runs on open floor, its walls left out); with any "
                  "source, the models' walls_from")
      ->check(CLI::ExistingFile);
  cmd->add_option("--hal", o->hal_url, "Drive one robot over ARCOS: tcp://HOST:PORT or serial:///dev/ttyS0");
  cmd->add_option("--truth-csv", o->truth_csv, "With --hal: the truth CSV p3at_sim --truth-csv is writing");
  cmd->add_option("--speedup", o->plan.speedup,
                  "With --hal to p3at_sim: its --speedup (rows are stamped in the robot's time)")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--from-log", o->from_log, "Fit a calibration log (docs/calibration.md) instead of driving");
  cmd->add_option("--robots", o->robots, "Robots to calibrate (default: every robot of the world or log)")
      ->delimiter(',');
  CLI::Option* mission = cmd->add_option(
      "--mission", o->mission_file,
      "Mission file: calibrate each of its robots at its own max_speed_mps and first Spin's rate (instead of "
      "--speed and --spin-rate; its robots are the default --robots)")->check(CLI::ExistingFile);
  cmd->add_option("--runs", o->plan.runs, "Runs per robot (each: 2 straights and 4 spins)")->check(CLI::Range(2, 100000));
  cmd->add_option("--speed", o->plan.speed_mps, "Straight-run speed, m/s: the mission speed (half of the straights at half of it)")
      ->check(CLI::Range(0.01, 2.0))
      ->excludes(mission);
  cmd->add_option("--distance", o->plan.distance_m, "Straight-run length, m (odometric)")->check(CLI::Range(0.2, 100.0));
  cmd->add_option("--spin-deg", o->plan.spin_deg, "Spin angle, degrees (odometric; 180 brings each run back)")
      ->check(CLI::Range(10.0, 720.0));
  cmd->add_option("--spin-rate", o->plan.spin_rate_degps, "Spin rate, deg/s: the mission's (half of the spins at half of it)")
      ->check(CLI::Range(1.0, 300.0))
      ->excludes(mission);
  cmd->add_option("--messages", o->messages, "Notifications to time over the simulated team link")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--peer-phase", o->peer_phase,
                  "Robots' cycles: lockstep (as in fast-time team runs) or random (unsynchronised robots)")
      ->check(CLI::IsMember({"lockstep", "random"}));
  cmd->add_option("--seed", o->seed, "Random seed of the simulated runs (default: the world file's, else 1)");
  cmd->add_option("--out", o->out_file, "Write the models file here (default: standard output)");
  cmd->add_option("--log-out", o->log_out, "Also write the calibration log (CSV) here");
  cmd->callback([o, &exit_status] { exit_status = run_calibrate(*o); });
}

}  // namespace p3at::vipars
