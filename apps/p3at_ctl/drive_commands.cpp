#include "drive_commands.hpp"

#include <algorithm>
#include <cmath>

namespace p3at::ctl {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kCycleTimeoutMs = 250;  // longer than a SIP period, shorter than link loss

double wrap_pi(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}

// Prints odometry at most every print_every_s of elapsed time.
class OdometryPrinter {
 public:
  OdometryPrinter(hal::Clock& clock, double every_s) : clock_(clock), start_us_(clock.now_us()), every_s_(every_s) {}
  void maybe_print(const hal::DriveState& state) {
    const double t = elapsed_s();
    if (t + 1e-9 >= next_s_) {
      print_odometry(stdout, t, state);
      next_s_ = t + every_s_;
    }
  }
  double elapsed_s() const { return static_cast<double>(clock_.now_us() - start_us_) / 1e6; }

 private:
  hal::Clock& clock_;
  std::int64_t start_us_;
  double every_s_;
  double next_s_ = 0.0;
};

bool link_ok(const bridge::ArcosClient& robot) {
  if (robot.state().link == hal::LinkState::ok) return true;
  std::fprintf(stderr, "p3at_ctl: link %s: %s\n", hal::to_string(robot.state().link),
               robot.state().why_stopped.c_str());
  return false;
}

// One control cycle: wait for the next SIP, then check the link.
bool cycle(bridge::ArcosClient& robot, OdometryPrinter& printer) {
  auto updated = robot.wait_for_update(kCycleTimeoutMs);
  if (!updated || !link_ok(robot)) return false;
  printer.maybe_print(robot.state());
  return true;
}

// Commands a velocity and waits one cycle; false (after saying why) on failure.
bool drive_cycle(bridge::ArcosClient& robot, OdometryPrinter& printer, double trans_mps, double rot_radps) {
  if (auto st = robot.set_velocity(trans_mps, rot_radps); !st) {
    std::fprintf(stderr, "p3at_ctl: %s\n", st.error().message.c_str());
    return false;
  }
  return cycle(robot, printer);
}

// Stops, lets the robot come to rest so the final odometry is the final pose, prints it.
int stop_and_report(bridge::ArcosClient& robot, OdometryPrinter& printer) {
  (void)robot.stop();
  for (int i = 0; i < 20 && std::fabs(robot.state().trans_vel_mps) + std::fabs(robot.state().rot_vel_radps) > 1e-3; ++i) {
    if (!cycle(robot, printer)) return 1;
  }
  print_odometry(stdout, printer.elapsed_s(), robot.state());
  return 0;
}

}  // namespace

void print_odometry_header(std::FILE* out) {
  std::fprintf(out, "%8s %9s %9s %9s %8s %8s %7s %s\n", "t_s", "x_m", "y_m", "th_deg", "v_mps", "w_dps", "batt_v",
               "motors");
}

void print_odometry(std::FILE* out, double t_s, const hal::DriveState& state) {
  std::fprintf(out, "%8.2f %9.3f %9.3f %9.2f %8.3f %8.2f %7.1f %s\n", t_s, state.odometry.x_m, state.odometry.y_m,
               state.odometry.theta_rad * 180.0 / kPi, state.trans_vel_mps, state.rot_vel_radps * 180.0 / kPi,
               state.battery_v, state.motors_enabled ? "on" : "off");
  std::fflush(out);
}

int drive_constant(bridge::ArcosClient& robot, hal::Clock& clock, const DriveOptions& options,
                   const std::atomic<bool>& interrupted) {
  OdometryPrinter printer(clock, options.print_every_s);
  print_odometry_header(stdout);
  while (printer.elapsed_s() < options.secs && !interrupted) {
    if (!drive_cycle(robot, printer, options.vel_mm_s / 1000.0, options.rotvel_deg_s * kPi / 180.0)) return 1;
  }
  return stop_and_report(robot, printer);
}

int drive_square(bridge::ArcosClient& robot, hal::Clock& clock, const DriveOptions& options,
                 const std::atomic<bool>& interrupted) {
  OdometryPrinter printer(clock, options.print_every_s);
  print_odometry_header(stdout);
  const double speed = (options.vel_mm_s > 0 ? options.vel_mm_s : 300.0) / 1000.0;
  const double turn_rate = (options.rotvel_deg_s > 0 ? options.rotvel_deg_s : 30.0) * kPi / 180.0;
  double heading = robot.state().odometry.theta_rad;
  for (int side = 0; side < 4 && !interrupted; ++side) {
    const hal::Pose2 start = robot.state().odometry;
    // Straight leg, holding the leg's heading; slow down over the last 0.3 m.
    while (!interrupted) {
      const hal::Pose2& p = robot.state().odometry;
      const double travelled = std::hypot(p.x_m - start.x_m, p.y_m - start.y_m);
      const double remaining = options.square_m - travelled;
      if (remaining <= 0.01) break;
      const double v = std::clamp(remaining / 0.3 * speed, 0.05, speed);
      const double w = std::clamp(2.0 * wrap_pi(heading - p.theta_rad), -turn_rate, turn_rate);
      if (!drive_cycle(robot, printer, v, w)) return 1;
    }
    // Turn 90° counter-clockwise in place.
    heading += kPi / 2;
    while (!interrupted) {
      const double error = wrap_pi(heading - robot.state().odometry.theta_rad);
      if (std::fabs(error) < 0.5 * kPi / 180.0) break;
      const double w = std::clamp(2.0 * error, -turn_rate, turn_rate);
      const double min_w = 3.0 * kPi / 180.0;  // the firmware's RVEL is in whole deg/s
      if (!drive_cycle(robot, printer, 0.0, std::fabs(w) < min_w ? std::copysign(min_w, w) : w)) return 1;
    }
  }
  return stop_and_report(robot, printer);
}

}  // namespace p3at::ctl
