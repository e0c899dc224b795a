#pragma once
// p3at_can_sim as a real process on the test interface, driven through its stdin.

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "can_test_env.hpp"

namespace p3at::test {

struct CanSimProcess {
  Child process;

  explicit CanSimProcess(std::vector<std::string> extra = {}) : process(make_args(extra), true) {
    REQUIRE_MESSAGE(process.wait_for_log("event=ready", 10.0), "p3at_can_sim did not start:\n" << process.log());
  }
  ~CanSimProcess() {
    if (process.running()) {
      process.send_line("quit");
      process.close_stdin();
      process.wait_exit(3.0);
    }
  }

  void command(const std::string& line) { REQUIRE(process.send_line(line)); }

  /// Sends "quit" and returns the exit code.
  int quit() {
    command("quit");
    process.close_stdin();
    return process.wait_exit(5.0);
  }

 private:
  static std::vector<std::string> make_args(const std::vector<std::string>& extra) {
    std::vector<std::string> args{P3AT_CAN_SIM_BIN, "--bus", can_url()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
};

}  // namespace p3at::test
