// main() of every serial-rig test executable: runs doctest only inside the rig
// of scripts/run-serial-tests.sh, where the tty under test is a real UART
// under the kernel's serial driver and its far end reaches this machine's
// P3AT_SERIAL_PEER_PORT. Anywhere else it prints "SKIPPED: <why>" and exits
// 77, which ctest reports as "Skipped" (never as passed): these tests drive
// whatever answers on the port, so they never touch a host's own ttyS0 unless
// told to. Inside the rig P3AT_REQUIRE_SERIAL=1 turns a skip into a failure,
// so CI cannot pass without running them.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "serial_rig.hpp"

namespace {

constexpr int kSkipExitCode = 77;

}  // namespace

int main(int argc, char** argv) {
  const std::string why = p3at::test::serial_rig::why_rig_unavailable();
  if (!why.empty()) {
    const char* require = std::getenv("P3AT_REQUIRE_SERIAL");
    if (require != nullptr && std::string(require) == "1") {
      std::printf("FAILED: %s, and P3AT_REQUIRE_SERIAL=1 says these tests must run here\n", why.c_str());
      return 1;
    }
    std::printf("SKIPPED: %s\n", why.c_str());
    return kSkipExitCode;
  }
  doctest::Context context(argc, argv);
  return context.run();
}
