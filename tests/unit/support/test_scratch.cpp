// tests/support/scratch.hpp: every path is new, in a directory no earlier
// process can have used, and the directory goes when its process does (but
// not when a forked child exits, and not with P3AT_KEEP_SCRATCH=1).

#include <sys/wait.h>
#include <unistd.h>

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "scratch.hpp"

namespace fs = std::filesystem;
using p3at::test::scratch_dir;
using p3at::test::scratch_path;

namespace {

/// Runs `body` in a forked child that then leaves through exit() (so static
/// destructors run, as in a test process's own end); its exit status.
template <typename Body>
int in_child(Body body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    body();
    std::exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("scratch paths are distinct, in one fresh directory whose name holds no process id") {
  std::set<std::string> seen;
  for (int i = 0; i < 5; ++i) CHECK(seen.insert(scratch_path("same.stem")).second);
  const fs::path root = fs::path(*seen.begin()).parent_path();
  for (const auto& p : seen) CHECK(fs::path(p).parent_path() == root);
  CHECK(fs::is_directory(root));
  CHECK(root.filename().string().rfind("p3at-test-", 0) == 0);
  CHECK(root.filename().string().find(std::to_string(::getpid())) == std::string::npos);
  const std::string dir = scratch_dir("a-directory");
  CHECK(fs::is_directory(dir));
  CHECK(fs::is_empty(dir));
}

TEST_CASE("a forked child's exit leaves the parent's scratch directory in place") {
  const std::string file = scratch_path("kept.txt");
  std::ofstream(file) << "the parent's";
  CHECK(in_child([] {}) == 0);
  CHECK(fs::exists(file));
}

TEST_CASE("a scratch root is removed with its contents when its owner ends it; kept with P3AT_KEEP_SCRATCH=1") {
  // A root made inside the child is owned by the child, as the one made by a
  // test process is owned by it; the child reports its path through a file.
  const std::string report = scratch_path("root-path.txt");
  const auto made_in_child = [&report](bool keep) {
    if (keep) ::setenv("P3AT_KEEP_SCRATCH", "1", 1);
    p3at::test::detail::ScratchRoot root;
    std::ofstream(root.path() / "inside") << "x";
    std::ofstream(report) << root.path().string();
  };
  REQUIRE(in_child([&] { made_in_child(false); }) == 0);
  std::string removed;
  std::ifstream(report) >> removed;
  REQUIRE_FALSE(removed.empty());
  CHECK_FALSE(fs::exists(removed));

  REQUIRE(in_child([&] { made_in_child(true); }) == 0);
  std::string kept;
  std::ifstream(report) >> kept;
  REQUIRE_FALSE(kept.empty());
  CHECK(kept != removed);
  CHECK(fs::exists(fs::path(kept) / "inside"));
  fs::remove_all(kept);
}
