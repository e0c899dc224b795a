#pragma once
// Helpers for the SocketCAN tests: the interface under test, shell commands,
// can-utils peers run as real processes, and child processes with a stdin pipe.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"

extern char** environ;

namespace p3at::test {

/// The CAN interface the tests use: $P3AT_CAN_IFACE, default vcan0.
inline std::string can_interface() {
  const char* env = std::getenv("P3AT_CAN_IFACE");
  return env != nullptr && *env != '\0' ? env : "vcan0";
}

inline std::string can_url() { return "socketcan://" + can_interface(); }

/// True when `tool` is an executable in a $PATH folder.
inline bool on_path(const std::string& tool) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((dir + "/" + tool).c_str(), X_OK) == 0) return true;
  }
  return false;
}

/// Runs a shell command, returns its exit status (-1 if it could not run).
inline int shell(const std::string& command) {
  const int rc = std::system(command.c_str());
  if (rc == -1 || !WIFEXITED(rc)) return -1;
  return WEXITSTATUS(rc);
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::int64_t steady_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// A child process (tests/support/child_process.hpp) whose log is a scratch
/// file, removed when the child is reaped.
class Child : public ChildProcess {
 public:
  explicit Child(std::vector<std::string> argv, bool with_stdin_pipe = false)
      : ChildProcess(std::move(argv), scratch_path("child.log"), with_stdin_pipe) {}
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    close_stdin();
    if (running()) {
      signal(SIGKILL);
      (void)wait_exit(5.0);
    }
    std::remove(log_path().c_str());
  }
};

}  // namespace p3at::test
