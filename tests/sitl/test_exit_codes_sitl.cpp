// Every binary's exit status for bad input is 2, as documented (README,
// docs/*.md): an unknown flag, a missing required argument, a malformed value
// or URL — never CLI11's own codes (105, 106, 109, 114) or 3. And the key
// file rules: a regular file readable by its owner only, never all zeros; a
// FIFO is refused at once instead of blocking. Each binary is run as a real
// process. Wall time: about 3 s.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

#include "team_fixture.hpp"

using namespace p3at;
using test::contains;

namespace {

struct Run {
  int status = -1;
  std::string output;
};

Run run(std::vector<std::string> argv, double timeout_s = 15.0) {
  const std::string log = test::scratch_path("exit.log");
  test::ChildProcess p(std::move(argv), log);
  Run r;
  r.status = p.wait_exit(timeout_s);
  r.output = p.log();
  return r;
}

const std::string kModels = std::string(P3AT_SOURCE_DIR) + "/tests/sitl/data/relay_models.yaml";

/// mission_exec for robot1 of the relay; the mission's own hal URL unless `extra` gives one
/// (a flag given twice is itself an argument error).
std::vector<std::string> exec_args(const std::string& key, std::vector<std::string> extra) {
  std::vector<std::string> a{P3AT_MISSION_EXEC_BIN, "--robot", "robot1", "--mission", test::kRelayMission,
                             "--models", kModels, "--team-key", key};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

std::string key_file(const std::string& text, ::mode_t mode) {
  const std::string path = test::scratch_path("k.key");
  std::ofstream(path) << text;
  ::chmod(path.c_str(), mode);
  return path;
}

}  // namespace

TEST_CASE("an unknown flag or a missing argument: exit 2 from every binary; --help: 0") {
  for (const std::string bin : {P3AT_MISSION_EXEC_BIN, P3AT_SIM_BIN, P3AT_CTL_BIN, P3AT_CAN_SIM_BIN,
                                P3AT_TEAM_KEY_BIN, P3AT_VIPARS_BIN}) {
    INFO(bin);
    CHECK(run({bin, "--no-such-flag"}).status == 2);
    CHECK(run({bin, "--help"}).status == 0);
  }
  CHECK(run({P3AT_MISSION_EXEC_BIN, "--robot", "robot1"}).status == 2);               // --mission required
  CHECK(run({P3AT_MISSION_EXEC_BIN, "--robot", "r", "--mission", "m", "--gate-timeout", "x"}).status == 2);
  CHECK(run({P3AT_SIM_BIN, "--port", "notaport"}).status == 2);
  CHECK(run({P3AT_TEAM_KEY_BIN}).status == 2);                                           // FILE required
  CHECK(run({P3AT_CTL_BIN}).status == 2);                                                // URL required
}

TEST_CASE("malformed URLs: exit 2 (mission_exec --hal / --lcm, p3at_ctl, p3at_can_sim --bus)") {
  const std::string key = test::make_key("team.key");
  const Run hal = run(exec_args(key, {"--hal", "tcp://127.0.0.1:notaport"}));
  CHECK(hal.status == 2);
  CHECK(contains(hal.output, "--hal: invalid URL"));
  CHECK(run(exec_args(key, {"--hal", "bogus://x"})).status == 2);
  const Run lcm = run(exec_args(key, {"--lcm", "udpm://nonsense", "--hal", "tcp://127.0.0.1:1"}));
  CHECK(lcm.status == 2);
  CHECK(contains(lcm.output, "is not an IPv4 multicast group"));
  CHECK(run(exec_args(key, {"--lcm", "udpm://239.255.76.67", "--hal", "tcp://127.0.0.1:1"})).status == 2);  // no port
  CHECK(run({P3AT_CTL_BIN, "tcp://127.0.0.1:notaport", "status"}).status == 2);
  CHECK(run({P3AT_CTL_BIN, "bogus://x", "status"}).status == 2);
  CHECK(run({P3AT_CAN_SIM_BIN, "--bus", "socketcan://"}).status == 2);
  CHECK(run({P3AT_CAN_SIM_BIN, "--bus", "bogus://x"}).status == 2);
}

TEST_CASE("--models naming a directory says so (exit 2), not 'empty models file'") {
  const std::string key = test::make_key("team.key");
  auto args = exec_args(key, {});
  args[6] = "/tmp";  // --models
  const Run r = run(args);
  CHECK(r.status == 2);
  CHECK(contains(r.output, "/tmp: is a directory, expected a file"));
}

TEST_CASE("key files: group- or world-readable, all zeros, a FIFO or a directory are refused (2; --check: 1)") {
  const std::string good_hex(std::string(63, '1') + "2");
  const std::string open_key = key_file(good_hex, 0644);
  const Run readable = run(exec_args(open_key, {}));
  CHECK(readable.status == 2);
  CHECK(contains(readable.output, "mode 0644 lets others read or write it"));
  CHECK(run({P3AT_TEAM_KEY_BIN, "--check", open_key}).status == 1);

  const std::string zero = key_file(std::string(64, '0'), 0600);
  const Run zeros = run(exec_args(zero, {}));
  CHECK(zeros.status == 2);
  CHECK(contains(zeros.output, "all zeros"));
  const Run check_zero = run({P3AT_TEAM_KEY_BIN, "--check", zero});
  CHECK(check_zero.status == 1);
  CHECK(contains(check_zero.output, "all zeros"));

  const std::string fifo = test::scratch_path("fifo.key");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const Run from_fifo = run(exec_args(fifo, {}), 5.0);  // used to block for ever
  CHECK(from_fifo.status == 2);
  CHECK(contains(from_fifo.output, "is a FIFO, not a regular file"));
  CHECK(run({P3AT_TEAM_KEY_BIN, "--check", fifo}, 5.0).status == 1);
  ::unlink(fifo.c_str());

  CHECK(run({P3AT_TEAM_KEY_BIN, "--check", "/tmp"}).status == 1);
  const std::string good = key_file(good_hex, 0600);
  const Run ok = run({P3AT_TEAM_KEY_BIN, "--check", good});
  CHECK(ok.status == 0);
  CHECK(contains(ok.output, "valid=1"));
}
