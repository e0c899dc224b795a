#include "p3at/sim/truth_csv.hpp"

#include <algorithm>
#include <cstdio>

namespace p3at::sim {

const char* truth_csv_header() {
  return "time_s,robot,true_x_m,true_y_m,true_theta_rad,odom_x_m,odom_y_m,odom_theta_rad,trans_vel_mps,"
         "rot_vel_radps,motion_commands";
}

std::string truth_csv_row(const World& world, std::size_t index) {
  const SimRobot& r = world.robot(index);
  const Pose& t = r.true_pose();
  const Pose o = r.odometry_in_world();
  char buf[320];
  const int n = std::snprintf(buf, sizeof buf, "%.1f,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%llu",
                              static_cast<double>(world.time_us()) / 1e6, r.name().c_str(), t.x_m, t.y_m,
                              t.theta_rad, o.x_m, o.y_m, o.theta_rad, r.true_trans_vel_mps(), r.true_rot_vel_radps(),
                              static_cast<unsigned long long>(r.controller().stats().motion_commands));
  if (n < 0) return {};
  return std::string(buf, std::min(static_cast<std::size_t>(n), sizeof buf - 1));
}

Result<std::unique_ptr<TruthCsvWriter>> TruthCsvWriter::open(const std::string& path) {
  std::ofstream out(path, std::ios::out | std::ios::trunc);
  if (!out) return make_error(Error::Code::not_found, "truth CSV " + path + ": cannot create file");
  out << truth_csv_header() << '\n';
  out.flush();
  if (!out) return make_error(Error::Code::io, "truth CSV " + path + ": cannot write");
  return std::unique_ptr<TruthCsvWriter>(new TruthCsvWriter(path, std::move(out)));
}

Status TruthCsvWriter::write_cycle(const World& world) {
  for (std::size_t i = 0; i < world.robot_count(); ++i) out_ << truth_csv_row(world, i) << '\n';
  out_.flush();
  if (!out_) return make_error(Error::Code::io, "truth CSV " + path_ + ": write failed");
  return {};
}

}  // namespace p3at::sim
