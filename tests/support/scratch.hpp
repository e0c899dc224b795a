#pragma once
// Scratch files for tests: every test process gets a directory of its own,
// made by mkdtemp and removed with its contents when the process exits.
//
// Why not "/tmp/<name>-<pid>-<n>": CI runs the whole suite several times
// (release, sanitizers) on one machine, and a process of a later stage can be
// given the PID of one from an earlier stage. Its scratch names then point at
// files left behind, and a tool that rightly refuses to replace a file
// (p3at_team_key without --force) fails the test. A fresh directory per
// process cannot meet anything old, and removing it at exit leaves nothing for
// the next stage to meet.
//
// Set P3AT_KEEP_SCRATCH=1 to keep the directory (its path is printed) for a
// look after a failure.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace p3at::test {

namespace detail {

class ScratchRoot {
 public:
  ScratchRoot() : owner_(::getpid()) {
    std::string pattern = (std::filesystem::temp_directory_path() / "p3at-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("scratch: mkdtemp failed for " + pattern);
    path_ = pattern;
    const char* keep = std::getenv("P3AT_KEEP_SCRATCH");
    keep_ = keep != nullptr && std::string(keep) == "1";
    if (keep_) std::fprintf(stderr, "[scratch] keeping %s\n", path_.c_str());
  }
  ~ScratchRoot() {
    // A forked child that exits runs this too: only the process that made
    // the directory removes it.
    if (keep_ || ::getpid() != owner_) return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchRoot(const ScratchRoot&) = delete;
  ScratchRoot& operator=(const ScratchRoot&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  pid_t owner_;
  bool keep_ = false;
};

inline const std::filesystem::path& scratch_root() {
  static const ScratchRoot root;
  return root.path();
}

}  // namespace detail

/// A path in this process's scratch directory that no other call returns
/// (nothing is created there).
inline std::string scratch_path(const std::string& stem) {
  static int counter = 0;
  return (detail::scratch_root() / (std::to_string(counter++) + "-" + stem)).string();
}

/// A new empty directory in this process's scratch directory.
inline std::string scratch_dir(const std::string& stem) {
  const std::string dir = scratch_path(stem);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace p3at::test
