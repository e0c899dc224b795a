#pragma once
/// Ground truth as CSV, one row per robot per cycle, flushed every cycle so
/// another process can follow it live:
///   time_s,robot,true_x_m,true_y_m,true_theta_rad,odom_x_m,odom_y_m,odom_theta_rad,
///   trans_vel_mps,rot_vel_radps,motion_commands
/// odom_* is the firmware's odometry in the world frame (start pose + odometry);
/// the velocities are the true ones.

#include <cstddef>
#include <fstream>
#include <memory>
#include <string>

#include "p3at/common/result.hpp"
#include "p3at/sim/world.hpp"

namespace p3at::sim {

/// The header line, without a newline.
const char* truth_csv_header();

/// One row for `world.robot(index)` at the world's current time, without a newline.
std::string truth_csv_row(const World& world, std::size_t index);

class TruthCsvWriter {
 public:
  /// Creates (truncates) `path` and writes the header. An unwritable path is an Error naming it.
  static Result<std::unique_ptr<TruthCsvWriter>> open(const std::string& path);

  /// Writes one row per robot and flushes.
  Status write_cycle(const World& world);

 private:
  TruthCsvWriter(std::string path, std::ofstream out) : path_(std::move(path)), out_(std::move(out)) {}
  std::string path_;
  std::ofstream out_;
};

}  // namespace p3at::sim
