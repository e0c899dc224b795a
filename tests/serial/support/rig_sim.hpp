#pragma once
// p3at_sim on the serial rig's peer port: the far end of /dev/ttyS0 is robot1.

#include <string>
#include <vector>

#include "child_process.hpp"
#include "serial_rig.hpp"

namespace p3at::test::serial_rig {

/// p3at_sim serving its robots from the peer port on (robot1 on the serial
/// line's far end, robot2 on the next port, reached over TCP).
struct SimOnPeerPort {
  std::string truth_path = scratch_path("truth.csv");
  ChildProcess process;

  explicit SimOnPeerPort(std::vector<std::string> extra = {})
      : process(args(extra, truth_path), scratch_path("p3at_sim.log")) {}

  /// Waits until the serial line's far end (QEMU) has connected `n` times in all.
  // 30 s: under host load QEMU (TCG) can take several kicks to reconnect; a
  // wait-until, so a healthy rig pays nothing for it.
  bool line_connected(int n, double timeout_s = 30.0) {
    const std::string needle = "connections=" + std::to_string(n) + "\n";
    return wait_for_line([&] { return process.log().find(needle) != std::string::npos; }, timeout_s);
  }

 private:
  static std::vector<std::string> args(const std::vector<std::string>& extra, const std::string& truth) {
    // All interfaces: QEMU's forward arrives on the guest's network address.
    std::vector<std::string> a{P3AT_SIM_BIN, "--port", std::to_string(peer_port()), "--host", "0.0.0.0",
                               "--truth-csv", truth};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
};

}  // namespace p3at::test::serial_rig
