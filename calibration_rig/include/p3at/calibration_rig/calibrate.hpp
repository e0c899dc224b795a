#pragma once
// `vipars calibrate`'s run (docs/calibration.md): the robot-models file the
// verifier reads, fitted from calibration data: simulated robots driven
// through the normal HAL (--world), one robot over ARCOS (--hal), or a log.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "p3at/calibration_rig/calibrate_drive.hpp"

namespace p3at::vipars {

struct CalibrateOptions {
  std::string world_file;
  std::string hal_url;
  std::string from_log;
  std::string truth_csv;
  std::vector<std::string> robots;
  /// A mission file: each of its robots is calibrated at its own
  /// max_speed_mps and its first Spin's rate (issue 13 item 9), in place of
  /// the one --speed / --spin-rate for all; its robots are the default
  /// --robots.
  std::string mission_file;
  ManoeuvrePlan plan;
  std::size_t messages = 400;
  std::string peer_phase = "lockstep";
  std::optional<std::uint64_t> seed;
  std::string out_file;
  std::string log_out;
};

/// Drives (or reads the log), fits, writes the models file; returns the exit
/// status (p3at/common/vipars_exit.hpp).
int run_calibrate(CalibrateOptions options);

}  // namespace p3at::vipars
