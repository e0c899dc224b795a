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

inline std::string scratch_file(const std::string& stem) {
  static int counter = 0;
  return "/tmp/p3at-can-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" + stem;
}

inline std::int64_t steady_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// A child process whose stdin is a pipe we write lines to and whose stdout and
/// stderr go to a log file. Killed and reaped on destruction.
class Child {
 public:
  Child(std::vector<std::string> argv, bool with_stdin_pipe = false) : log_path_(scratch_file("child.log")) {
    int fds[2] = {-1, -1};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (with_stdin_pipe) {
      if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
      posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
      posix_spawn_file_actions_addclose(&actions, fds[0]);
      posix_spawn_file_actions_addclose(&actions, fds[1]);
    } else {
      posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    }
    posix_spawn_file_actions_addopen(&actions, 1, log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    const int rc = ::posix_spawnp(&pid_, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (with_stdin_pipe) {
      ::close(fds[0]);
      stdin_fd_ = fds[1];
    }
    if (rc != 0) throw std::runtime_error("cannot start " + argv[0]);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    close_stdin();
    if (running()) {
      ::kill(pid_, SIGKILL);
      wait_exit(5.0);
    }
    std::remove(log_path_.c_str());
  }

  /// Writes one command line to the child's stdin.
  bool send_line(const std::string& line) {
    const std::string text = line + "\n";
    return stdin_fd_ >= 0 && ::write(stdin_fd_, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  }
  void close_stdin() {
    if (stdin_fd_ >= 0) ::close(stdin_fd_);
    stdin_fd_ = -1;
  }

  std::string log() const { return read_text(log_path_); }

  /// Waits until the log contains `needle`; false on timeout or exit without it.
  bool wait_for_log(const std::string& needle, double timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < deadline) {
      if (log().find(needle) != std::string::npos) return true;
      if (!running()) return log().find(needle) != std::string::npos;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  void signal(int sig) {
    if (!exited_) ::kill(pid_, sig);
  }

  bool running() {
    if (exited_) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      exited_ = true;
      status_ = status;
    }
    return !exited_;
  }

  /// Exit code (128 + signal when killed), or -1 on timeout.
  int wait_exit(double timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (running()) {
      if (std::chrono::steady_clock::now() > deadline) return -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (WIFEXITED(status_)) return WEXITSTATUS(status_);
    if (WIFSIGNALED(status_)) return 128 + WTERMSIG(status_);
    return -1;
  }

 private:
  std::string log_path_;
  pid_t pid_ = -1;
  int stdin_fd_ = -1;
  bool exited_ = false;
  int status_ = 0;
};

}  // namespace p3at::test
