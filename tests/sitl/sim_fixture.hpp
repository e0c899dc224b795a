#pragma once
// Starts p3at_sim as a real process on a free port and waits until it listens.

#include <string>
#include <vector>

#include "child_process.hpp"

namespace p3at::test {

struct SimProcess {
  int port = free_tcp_port();
  std::string log_path = scratch_path("p3at_sim.log");
  std::string truth_path = scratch_path("truth.csv");
  ChildProcess process;

  explicit SimProcess(std::vector<std::string> extra_args = {}, int fixed_port = 0)
      : port(fixed_port != 0 ? fixed_port : free_tcp_port()), process(make_args(extra_args), log_path) {}

  std::string url() const { return "tcp://127.0.0.1:" + std::to_string(port); }
  bool ready(double timeout_s = 10.0) { return process.wait_for_log("port=" + std::to_string(port), timeout_s); }

 private:
  std::vector<std::string> make_args(const std::vector<std::string>& extra) const {
    std::vector<std::string> args{P3AT_SIM_BIN, "--port", std::to_string(port), "--truth-csv", truth_path};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
};

}  // namespace p3at::test
