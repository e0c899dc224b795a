// p3at_ctl over a real serial driver (serial rig, docs/hal.md): the engineer's
// console reaches p3at_sim through /dev/ttyS0 exactly as it reaches a robot's
// controller through a serial cable: status, then a drive the simulator's
// ground truth confirms.
#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "rig_sim.hpp"
#include "serial_rig.hpp"

using namespace p3at::test::serial_rig;
using p3at::test::ChildProcess;
using p3at::test::scratch_path;

namespace {

bool contains(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

/// robot1's first and last true x (m) in p3at_sim's truth CSV.
std::pair<double, double> first_last_true_x(const std::string& csv) {
  std::ifstream in(csv);
  double first = 0, last = 0;
  bool any = false;
  for (std::string line; std::getline(in, line);) {
    double t = 0, x = 0;
    char name[64] = {};
    if (std::sscanf(line.c_str(), "%lf,%63[^,],%lf", &t, name, &x) == 3 && std::string(name) == "robot1") {
      if (!any) first = x;
      last = x;
      any = true;
    }
  }
  return {first, any ? last : first - 1.0};
}

}  // namespace

TEST_CASE("p3at_ctl status over /dev/ttyS0 reads the robot's identity, config and SIPs") {
  SimOnPeerPort sim;
  REQUIRE_MESSAGE(sim.line_connected(1), sim.process.log());
  ChildProcess ctl({P3AT_CTL_BIN, url(9600), "status"}, scratch_path("ctl.log"));
  const int rc = ctl.wait_exit(60.0);
  const std::string out = ctl.log();
  INFO(out);
  INFO(sim.process.log());
  CHECK(rc == 0);
  CHECK(contains(out, "robot     name=robot1 class=Pioneer subclass=p3at"));
  CHECK(contains(out, "config    serial=SIM"));
  CHECK(contains(out, "trans_vel_max_mm_s="));
  CHECK_FALSE(contains(out, "trans_vel_max_mm_s=0 "));
  CHECK(contains(out, "motors=enabled"));
  // No corrupted packet. (A packet stretched past ARCOS's 100 ms inter-byte
  // timeout by the emulated machine's stalls is dropped and counted as a
  // timeout, as a real client would; that is not the line's fault.)
  const std::size_t link = out.find("link      sips=");
  REQUIRE(link != std::string::npos);
  unsigned long long sips = 0, bad_header = 0, bad_checksum = 0, bad_count = 0, timeouts = 0;
  REQUIRE(std::sscanf(out.c_str() + link, "link      sips=%llu bad_header=%llu bad_checksum=%llu bad_count=%llu timeouts=%llu",
                      &sips, &bad_header, &bad_checksum, &bad_count, &timeouts) == 5);
  CHECK(sips >= 5);
  CHECK(bad_checksum == 0);
  CHECK(bad_count == 0);
  // The firmware saw the serial preamble (garbage to it) and a clean session.
  CHECK(sim.process.wait_for_log("disconnect robot=robot1 reason=", 10.0));
}

TEST_CASE("p3at_ctl drive over /dev/ttyS0 moves the simulated robot") {
  SimOnPeerPort sim;
  REQUIRE_MESSAGE(sim.line_connected(1), sim.process.log());
  ChildProcess ctl({P3AT_CTL_BIN, url(38400), "drive", "--vel", "300", "--secs", "2"}, scratch_path("ctl.log"));
  const int rc = ctl.wait_exit(60.0);
  const std::string out = ctl.log();
  INFO(out);
  CHECK(rc == 0);
  // The last odometry line: t_s x_m y_m ...; the robot went forward.
  const std::size_t last = out.find_last_of('\n', out.size() - 2);
  double t_s = 0, x_m = 0;
  REQUIRE(std::sscanf(out.c_str() + (last == std::string::npos ? 0 : last + 1), "%lf %lf", &t_s, &x_m) == 2);
  CHECK(x_m > 0.3);
  CHECK(x_m < 0.8);
  // The simulator's ground truth agrees that robot1 moved.
  REQUIRE(sim.process.wait_for_log("disconnect robot=robot1", 10.0));
  sim.process.signal(SIGTERM);
  CHECK(sim.process.wait_exit(10.0) == 0);
  const auto [x0, x1] = first_last_true_x(sim.truth_path);
  CHECK(x1 - x0 > 0.3);
}
