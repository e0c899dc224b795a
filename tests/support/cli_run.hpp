#pragma once
// Running a command line as a user would (through the shell) for the CLI
// tests: its exit status, stdout and stderr captured separately (stderr
// carries timing, stdout must not); and reading or writing a whole file.

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scratch.hpp"

namespace p3at::test {

/// The vipars binary the build made (P3AT_VIPARS_BIN, set by the test's
/// CMake target), else the one beside the running test, never one on PATH.
inline std::string vipars_binary() {
#ifdef P3AT_VIPARS_BIN
  return P3AT_VIPARS_BIN;
#else
  return (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "vipars").string();
#endif
}

/// The whole file, bytes as they are; "" if it cannot be read.
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Writes `text` as the whole file.
inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// What a command did: its exit status (-1 if it did not exit, e.g. killed
/// by a signal), its stdout and its stderr.
struct CommandOutcome {
  int status = -1;
  std::string out;
  std::string err;
};

/// Runs `command` with /bin/sh, in `dir` when given; a redirection inside
/// `command` stays its own, the rest of stdout and stderr is captured.
inline CommandOutcome run_command(const std::string& command, const std::string& dir = "") {
  const std::string stem = scratch_path("command");
  const std::string out = stem + ".stdout", err = stem + ".stderr";
  const std::string cd = dir.empty() ? std::string() : "cd '" + dir + "' && ";
  const std::string full = cd + "{ " + command + " ; } >'" + out + "' 2>'" + err + "'";
  const int raw = std::system(full.c_str());
  CommandOutcome o;
  o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  o.out = read_file(out);
  o.err = read_file(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return o;
}

}  // namespace p3at::test
