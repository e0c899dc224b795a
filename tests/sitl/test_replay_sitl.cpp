// A recording of one run played into the next (docs/team-link.md, "Sessions
// and replays"): lcm-logger records a whole relay (p3at_sim, two mission_exec
// over real LCM on the loopback); lcm-logplayer then plays it, sped up, into
// the same channels with the same team key while (1) robot1 runs alone: the
// recorded GO of robot2 never launches it, the recorded status and telemetry
// are rejected_other_session, and the simulator counts no motion; (2) both
// robots run again: the recorded r1_done never fires robot2's Notified, so
// robot2 starts moving only once the real robot1 has reached its goal.
// Wall time: about 35 s (three runs at --speedup 4). Skipped, saying so, when
// liblcm-bin's lcm-logger or lcm-logplayer is missing (CI installs it).
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <thread>

#include "gate_bench.hpp"

using namespace p3at;
using test::contains;

namespace {

bool have_lcm_tools() {
  return !std::string(P3AT_LCM_LOGGER_BIN).empty() && !std::string(P3AT_LCM_LOGPLAYER_BIN).empty();
}

/// The counter `name=` of the event=team-link line, or -1.
long long counter(const std::string& log, const std::string& name) {
  const auto pos = log.find("event=team-link");
  if (pos == std::string::npos) return -1;
  const auto at = log.find(" " + name + "=", pos);
  if (at == std::string::npos) return -1;
  return std::stoll(log.substr(at + name.size() + 2));
}

test::ChildProcess play(const std::string& lcm, const std::string& log) {
  return test::ChildProcess({P3AT_LCM_LOGPLAYER_BIN, "--speed=3", "--lcm-url=" + lcm, log},
                            test::scratch_path("lcm-logplayer.log"));
}

}  // namespace

TEST_CASE("a recorded run played into the next: nothing fires, nothing launches" *
          doctest::skip(!have_lcm_tools())) {
  // ---- run 1, recorded
  std::string lcm, key, recording = test::scratch_path("run1.lcmlog");
  {
    test::Bench bench;
    lcm = bench.lcm;
    key = bench.key;
    test::ChildProcess logger({P3AT_LCM_LOGGER_BIN, "-f", "--flush-interval=50", "--lcm-url=" + lcm, recording},
                              test::scratch_path("lcm-logger.log"));
    for (int i = 0; i < 200 && ::access(recording.c_str(), F_OK) != 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    test::ChildProcess robot2(bench.args("robot2"), test::scratch_path("run1-robot2.log"));
    REQUIRE(robot2.wait_for_log("event=gate-open", 15.0));
    test::ChildProcess robot1(bench.args("robot1"), test::scratch_path("run1-robot1.log"));
    REQUIRE(robot1.wait_exit(90.0) == 0);
    REQUIRE(robot2.wait_exit(90.0) == 0);
    logger.signal(SIGINT);
    CHECK(logger.wait_exit(10.0) == 0);
    REQUIRE(test::read_file(recording).size() > 10'000);
  }

  {  // robot1 alone: robot2's recorded GO never launches it
    test::Bench bench;
    bench.lcm = lcm;
    bench.key = key;
    test::ChildProcess robot1(bench.args("robot1", {"--gate-timeout", "4"}), test::scratch_path("robot1.log"));
    REQUIRE(robot1.wait_for_log("event=gate-open", 15.0));
    auto player = play(lcm, recording);
    CHECK(robot1.wait_exit(30.0) == test::kExitGateSilent);
    const std::string log = robot1.log();
    INFO("robot1 log:\n" << log);
    CHECK_FALSE(contains(log, "event=verdict-heard"));   // the recorded verdicts echo another gate's nonce
    CHECK(counter(log, "verdicts_accepted") > 0);        // they were authentic and heard...
    CHECK(counter(log, "rejected_other_session") > 0);   // ...and the recorded status / telemetry rejected
    CHECK(contains(log, "(heard robot2, but not hearing this robot)"));
    bench.check_no_motion();
  }

  {  // both robots again: the recorded r1_done does not fire robot2 before the real robot1 is at its goal
    test::Bench bench;
    bench.lcm = lcm;
    bench.key = key;
    test::ChildProcess robot2(bench.args("robot2"), test::scratch_path("robot2.log"));
    REQUIRE(robot2.wait_for_log("event=gate-open", 15.0));
    // The recording starts before robot1 does: at 3x, its r1_done comes while
    // the real robot1 is still driving.
    auto player = play(lcm, recording);
    test::ChildProcess robot1(bench.args("robot1"), test::scratch_path("robot1.log"));
    CHECK(robot1.wait_exit(90.0) == 0);
    CHECK(robot2.wait_exit(90.0) == 0);
    const std::string log2 = robot2.log();
    INFO("robot2 log:\n" << log2);
    INFO("robot1 log:\n" << robot1.log());
    CHECK(counter(log2, "rejected_other_session") > 0);
    CHECK(counter(log2, "accepted") == 1);  // the one real r1_done
    // From the simulator's truth: robot2 left its start only once robot1 was near (3, 1).
    const auto rows1 = test::truth_rows(bench.sim.truth_path, "robot1");
    const auto rows2 = test::truth_rows(bench.sim.truth_path, "robot2");
    REQUIRE_FALSE(rows2.empty());
    double moved_at_s = -1;
    for (const auto& r : rows2) {
      if (r.x_m > rows2.front().x_m + 0.05) {
        moved_at_s = r.time_s;
        break;
      }
    }
    REQUIRE(moved_at_s >= 0);
    double robot1_x = 0;
    for (const auto& r : rows1) {
      if (r.time_s <= moved_at_s) robot1_x = r.x_m;
    }
    INFO("robot2 moved at t=" << moved_at_s << " s, robot1 then at x=" << robot1_x);
    CHECK(robot1_x > 2.6);
  }
}
