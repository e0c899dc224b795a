// The launch gate's guarantee, checked on real processes (docs/launch-gate.md,
// "What the agreement guarantees"): p3at_sim serving two robots, two
// mission_exec over real LCM multicast on the loopback and real TCP. robot1
// opens its gate (timeout 2 s); robot2 starts at offsets swept across that
// timeout, including the second after it, when robot1 has refused but is
// still telling the team why (the window in which, before sessions, robot2
// launched on robot1's stale GO). robot2 says GO, NO-GO (--tmax 5), holds the
// wrong key, or never starts. After each case, from the simulator's own
// counters: whenever either robot refused, neither received a motion command.
// Wall time: about 12 cases of 4 to 8 s each, 60 to 90 s in all on an idle
// 2-core machine (sitl label, TIMEOUT 300).
#include <doctest/doctest.h>

#include <chrono>
#include <optional>
#include <utility>
#include <string>
#include <thread>
#include <vector>

#include "gate_bench.hpp"

using namespace p3at;
using test::contains;

namespace {

// Under the sanitizers (-O0) a robot takes far longer to start and verify, so
// where in the sweep the outcome changes moves; the guarantee is checked all
// the same, the expected outcome at each offset only in the optimised build.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kTimingAsReleased = false;
#else
constexpr bool kTimingAsReleased = true;
#endif

enum class Teammate { go, no_go, wrong_key, absent };

const char* name_of(Teammate t) {
  switch (t) {
    case Teammate::go: return "GO";
    case Teammate::no_go: return "NO-GO";
    case Teammate::wrong_key: return "wrong key";
    case Teammate::absent: return "absent";
  }
  return "?";
}

bool is_refusal(int status) {
  return status == test::kExitGateNoGo || status == test::kExitGateMismatch || status == test::kExitGateSilent;
}

struct Outcome {
  int robot1 = -1;
  int robot2 = -1;  ///< -1: never started
  std::string log1, log2;
};

/// One case: robot1 at 0, robot2 `offset_s` after robot1's gate opened.
Outcome run_case(Teammate teammate, double offset_s) {
  test::Bench bench;
  Outcome out;
  const std::vector<std::string> timeout{"--gate-timeout", "2"};
  test::ChildProcess robot1(bench.args("robot1", timeout), test::scratch_path("robot1.log"));
  REQUIRE(robot1.wait_for_log("event=gate-open", 15.0));
  std::this_thread::sleep_for(std::chrono::duration<double>(offset_s));
  std::optional<test::ChildProcess> robot2;
  if (teammate != Teammate::absent) {
    std::vector<std::string> extra = timeout;
    if (teammate == Teammate::no_go) extra.insert(extra.end(), {"--tmax", "5"});
    auto args = bench.args("robot2", extra);
    if (teammate == Teammate::wrong_key) {
      const std::string other = test::make_key("other.key");
      for (std::size_t i = 0; i + 1 < args.size(); ++i) {
        if (args[i] == "--team-key") args[i + 1] = other;
      }
    }
    robot2.emplace(args, test::scratch_path("robot2.log"));
  }
  // Both decide within timeout + linger + doubt; a launched robot is stopped
  // after 1.5 s of mission, so the simulator has seen it move.
  const auto settle = [](test::ChildProcess& p) {
    if (!p.wait_for_log("event=gate-decision", 20.0)) return -1;
    if (p.wait_for_log("event=launch", 0.3)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      p.signal(SIGTERM);
    }
    return p.wait_exit(20.0);
  };
  out.robot1 = settle(robot1);
  if (robot2) out.robot2 = settle(*robot2);
  out.log1 = robot1.log();
  if (robot2) out.log2 = robot2->log();
  INFO("robot1 log:\n" << out.log1);
  INFO("robot2 log:\n" << out.log2);
  // Nobody hangs, nobody is in doubt on a loss-free loopback.
  CHECK(out.robot1 != -1);
  CHECK(out.robot1 != test::kExitGateInDoubt);
  CHECK(out.robot2 != test::kExitGateInDoubt);
  if (is_refusal(out.robot1) || is_refusal(out.robot2)) {
    // The guarantee: a refusal anywhere, no motion anywhere.
    bench.check_no_motion();
  } else {
    // Both launched (and were stopped by SIGTERM: exit 3); the counter that
    // the refusals rely on does see motion when there is some.
    CHECK(out.robot1 == test::kExitAborted);
    CHECK(out.robot2 == test::kExitAborted);
    CHECK(test::motion_commands(bench.sim.truth_path, "robot1") > 0);
  }
  return out;
}

}  // namespace

TEST_CASE("start times swept across the gate timeout: whenever a robot refused, no robot received a motion command") {
  int launched = 0, refused = 0, heard_refusal = 0;
  for (const double offset_s : {0.3, 1.2, 1.7, 1.9, 2.1, 2.3, 2.6, 3.6}) {
    INFO("robot2 GO, " << offset_s << " s after robot1's gate opened");
    const Outcome o = run_case(Teammate::go, offset_s);
    (is_refusal(o.robot1) || is_refusal(o.robot2)) ? ++refused : ++launched;
    if (offset_s < 1.0 && kTimingAsReleased) {
      CHECK(o.robot1 == test::kExitAborted);  // launched together (then stopped)
    }
    if (offset_s >= 2.1 && offset_s <= 2.6) {
      // robot1 refused at 2 s and is still telling why: robot2 hears the
      // refusal, not the GO robot1 published before it (or, if it came up
      // after robot1 left, nobody at all).
      // Which of the two depends on how long robot2 takes to come up: on a
      // loaded machine (CI runs the accuracy gate beside these) robot2 came
      // up 2.6 s after robot1's gate opened only after robot1 had left. So
      // each case accepts both, and the window itself must be hit at least
      // once over the three offsets (checked after the sweep).
      CHECK(o.robot1 == test::kExitGateSilent);
      if (o.robot2 == test::kExitGateNoGo) {
        ++heard_refusal;
        CHECK(contains(o.log2, "teammate robot1 says NO-GO"));
        CHECK(contains(o.log2, "refused: no verdict from robot2"));
      } else {
        CHECK(o.robot2 == test::kExitGateSilent);
      }
    }
    if (offset_s > 3.5) {
      CHECK(o.robot1 == test::kExitGateSilent);
      CHECK(o.robot2 == test::kExitGateSilent);
    }
  }
  MESSAGE("swept: launched=" << launched << " refused=" << refused);
  if (kTimingAsReleased) CHECK(launched >= 1);
  // robot2 heard robot1's refusal (not its earlier GO) in the window at least once.
  if (kTimingAsReleased) CHECK(heard_refusal >= 1);
  CHECK(refused >= 3);
}

TEST_CASE("a NO-GO teammate, early or late, a wrong key and an absent teammate: refusals, and no motion") {
  for (const auto& one_case : std::vector<std::pair<Teammate, double>>{
           {Teammate::no_go, 0.3}, {Teammate::no_go, 2.3}, {Teammate::wrong_key, 0.3}, {Teammate::absent, 0.0}}) {
    // (named copies, not a structured binding: INFO's lambda captures them,
    // which clang 14 does not allow for bindings)
    const Teammate teammate = one_case.first;
    const double offset_s = one_case.second;
    INFO("robot2 " << name_of(teammate) << ", " << offset_s << " s after robot1's gate opened");
    const Outcome o = run_case(teammate, offset_s);
    CHECK(is_refusal(o.robot1));
    switch (teammate) {
      case Teammate::no_go:
        CHECK(o.robot2 == test::kExitGateNoGo);
        if (offset_s < 1.0 && kTimingAsReleased) CHECK(contains(o.log1, "teammate robot2 says NO-GO"));
        break;
      case Teammate::wrong_key:
        // The refusal names the likely cause: robot2's messages fail their tags.
        CHECK(o.robot1 == test::kExitGateSilent);
        CHECK(o.robot2 == test::kExitGateSilent);
        if (kTimingAsReleased) {
          CHECK(contains(o.log1, "wrong team key?"));
          CHECK(contains(o.log2, "wrong team key?"));
        }
        break;
      case Teammate::absent:
        CHECK(o.robot1 == test::kExitGateSilent);
        break;
      case Teammate::go: break;
    }
  }
}
