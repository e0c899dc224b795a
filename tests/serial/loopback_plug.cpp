// serial_loopback_plug: a loopback plug for the serial rig. Echoes every byte
// that arrives on the tty's far end back down the line (TX jumpered to RX, as
// docs/hal.md describes for a USB-serial adapter), then runs COMMAND with
// P3AT_TEST_SERIAL_URL and P3AT_TEST_SERIAL_LOOPBACK=1 set, so unit_hal's
// opt-in hardware check runs in CI exactly as it would on an adapter.
//   serial_loopback_plug BAUD COMMAND [ARGS...]
// Exit status: COMMAND's; 77 (skipped) outside the rig; 2 on bad usage or a
// line that never connected.
#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "serial_rig.hpp"

extern char** environ;

int main(int argc, char** argv) {
  using namespace p3at::test::serial_rig;
  if (argc < 3) {
    std::fprintf(stderr, "usage: serial_loopback_plug BAUD COMMAND [ARGS...]\n");
    return 2;
  }
  const std::string why = why_rig_unavailable();
  if (!why.empty()) {
    const char* require = std::getenv("P3AT_REQUIRE_SERIAL");
    if (require != nullptr && std::string(require) == "1") {
      std::printf("FAILED: %s, and P3AT_REQUIRE_SERIAL=1 says this must run here\n", why.c_str());
      return 1;
    }
    std::printf("SKIPPED: %s\n", why.c_str());
    return 77;
  }
  const std::string line_url = url(std::atoi(argv[1]));
  FarEnd plug([](p3at::hal::ByteStream& line, const std::atomic<bool>& stop) {
    std::vector<std::uint8_t> buffer(256);
    while (!stop) {
      auto got = line.read_some(buffer, 20);
      if (!got.ok()) return;
      if (*got > 0 && !line.write_all(std::span<const std::uint8_t>(buffer.data(), *got)).ok()) return;
    }
  });
  if (!plug.wait_connected()) {
    std::fprintf(stderr, "serial_loopback_plug: the line's far end never connected to port %d\n", peer_port());
    return 2;
  }
  ::setenv("P3AT_TEST_SERIAL_URL", line_url.c_str(), 1);
  ::setenv("P3AT_TEST_SERIAL_LOOPBACK", "1", 1);
  std::printf("serial_loopback_plug: %s looped back; running %s\n", line_url.c_str(), argv[2]);
  std::fflush(stdout);
  pid_t pid = -1;
  if (::posix_spawnp(&pid, argv[2], nullptr, nullptr, argv + 2, environ) != 0) {
    std::fprintf(stderr, "serial_loopback_plug: cannot start %s\n", argv[2]);
    return 2;
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return 2;
  plug.stop();
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}
