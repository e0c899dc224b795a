// run_realtime: paced by wait_for_update, runs the cycle anyway on a missed
// update, stops the robot at the end, honours the stop flag, lingers for teammates.

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <functional>

#include "fake_clock.hpp"
#include "fake_drive_base.hpp"
#include "fake_team_link.hpp"
#include "mission_builder.hpp"
#include "p3at/common/log.hpp"
#include "p3at/executive/realtime_loop.hpp"

namespace mission = p3at::mission;
using p3at::exec::Phase;
using p3at::exec::RobotExecutive;
using p3at::test::FakeClock;
using p3at::test::FakeDriveBase;
using p3at::test::FakeTeamLink;
using p3at::test::RobotBuilder;

namespace {

/// A FakeDriveBase whose wait_for_update first calls a hook (the test's script).
class ScriptedDrive final : public p3at::hal::DriveBase {
 public:
  explicit ScriptedDrive(FakeDriveBase& inner) : inner_(inner) {}
  p3at::Status set_velocity(double v, double w) override { return inner_.set_velocity(v, w); }
  p3at::Status stop() override { return inner_.stop(); }
  p3at::Status emergency_stop() override { return inner_.emergency_stop(); }
  p3at::Result<bool> wait_for_update(int timeout_ms) override {
    ++calls;
    if (hook) {
      if (auto r = hook(calls, timeout_ms)) return *r;
    }
    return inner_.wait_for_update(timeout_ms);
  }
  const p3at::hal::DriveState& state() const override { return inner_.state(); }

  int calls = 0;
  /// Returns a result to short-circuit the inner base, or nullopt to pass through.
  std::function<std::optional<p3at::Result<bool>>(int call, int timeout_ms)> hook;

 private:
  FakeDriveBase& inner_;
};

mission::Mission spin_then_wait() {
  RobotBuilder r("robot1", {0, 0, 0});
  r.state("turn", mission::SpinParams{30.0}).state("wait", mission::StopParams{});
  r.state("end", mission::StopParams{});
  r.transition("turn", "wait", mission::HasTurnedParams{90.0, 1.5});
  r.transition("wait", "end", mission::NotifiedParams{"go"});
  RobotBuilder mate("robot2", {0, 5, 0});
  mate.state("idle", mission::StopParams{});
  return p3at::test::make_mission({r.build(), mate.build()}, {mission::Message{"go", 1, {0}}});
}

struct Rig {
  Rig() : inner(&clock), drive(inner), link("robot1"), exec(spin_then_wait(), 0, drive, link, clock) {
    p3at::log::threshold() = p3at::log::Level::error;
  }
  FakeClock clock{0};
  FakeDriveBase inner;
  ScriptedDrive drive;
  FakeTeamLink link;
  RobotExecutive exec;
  std::atomic<bool> stop{false};
};

}  // namespace

TEST_CASE("run_realtime: one cycle per update until finished, then the robot is stopped") {
  Rig rig;
  rig.drive.hook = [&](int call, int) -> std::optional<p3at::Result<bool>> {
    if (call == 40) rig.link.deliver("robot2", "go");
    return std::nullopt;
  };
  const auto outcome = p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop);
  CHECK(outcome.phase == Phase::finished);
  CHECK(rig.exec.state_name() == "end");
  CHECK(rig.drive.calls == 40);
  CHECK(rig.exec.stats().cycles() == 40);
  CHECK(rig.exec.stats().missed_updates() == 0);
  CHECK(rig.inner.stop_calls == 2);  // once on finishing, once more by the loop on the way out
  CHECK(rig.clock.now_us() == 40 * 100'000);  // paced by the updates, nothing else
}

TEST_CASE("run_realtime: a missing update counts as missed and the cycle runs anyway") {
  Rig rig;
  rig.drive.hook = [&](int call, int) -> std::optional<p3at::Result<bool>> {
    rig.inner.deliver_updates = !(call >= 5 && call < 8);  // calls 5, 6, 7 time out (150 ms each)
    if (call == 12) rig.stop = true;
    return std::nullopt;
  };
  const auto outcome = p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop);
  CHECK(rig.exec.stats().cycles() == 12);
  CHECK(rig.exec.stats().missed_updates() == 3);
  CHECK(rig.clock.now_us() == 9 * 100'000 + 3 * 150'000);
  CHECK(outcome.phase == Phase::aborted);
  CHECK(outcome.reason == "interrupted");
  CHECK(rig.inner.stop_calls >= 1);
  CHECK(rig.inner.trans_cmd_mps == 0.0);
  CHECK(rig.inner.rot_cmd_radps == 0.0);
}

TEST_CASE("run_realtime: a stall (this process not running) is counted; past stall_abort_ms it aborts, or resumes") {
  // The hook makes update 5 arrive 300 ms of real wall time late (the process
  // was not running); wait_for_update(0), the drain, finds nothing queued.
  const auto stall_at_5 = [](Rig& rig, int stop_at) {
    return [&rig, stop_at](int call, int timeout_ms) -> std::optional<p3at::Result<bool>> {
      if (timeout_ms == 0) return p3at::Result<bool>(false);
      if (call == 5) std::this_thread::sleep_for(std::chrono::milliseconds(300));
      if (call == stop_at) rig.stop = true;
      return std::nullopt;
    };
  };
  SUBCASE("shorter than stall_abort_ms: counted and logged, the mission goes on") {
    Rig rig;
    rig.drive.hook = stall_at_5(rig, 12);
    p3at::exec::RealtimeOptions options;
    const auto outcome = p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop, options);
    CHECK(rig.exec.stats().stalls() == 1);
    CHECK(rig.exec.stats().missed_cycles() >= 2);  // 300 ms of wall time: at least 2 periods not run
    CHECK(rig.exec.stats().longest_stall_ms() >= 300);
    CHECK(outcome.reason == "interrupted");       // ended by the stop flag, not by the stall
  }
  SUBCASE("longer than stall_abort_ms: aborted, saying why") {
    Rig rig;
    rig.drive.hook = stall_at_5(rig, 50);
    p3at::exec::RealtimeOptions options;
    options.stall_abort_ms = 200;
    const auto outcome = p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop, options);
    CHECK(outcome.phase == Phase::aborted);
    CHECK(outcome.reason.find("longer than the firmware watchdog (200 ms)") != std::string::npos);
    CHECK(rig.exec.stats().cycles() == 5);
  }
  SUBCASE("longer, with resume_after_stall: it goes on") {
    Rig rig;
    rig.drive.hook = stall_at_5(rig, 12);
    p3at::exec::RealtimeOptions options;
    options.stall_abort_ms = 200;
    options.resume_after_stall = true;
    const auto outcome = p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop, options);
    CHECK(outcome.reason == "interrupted");
    CHECK(rig.exec.stats().stalls() == 1);
  }
}

TEST_CASE("run_realtime: a base that fails at once cannot make the loop spin faster than the period") {
  Rig rig;
  rig.drive.hook = [&](int call, int) -> std::optional<p3at::Result<bool>> {
    if (call == 10) rig.stop = true;
    if (call > 1) return p3at::Result<bool>(p3at::make_error(p3at::Error::Code::io, "read failed"));
    return std::nullopt;
  };
  (void)p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop);
  CHECK(rig.exec.stats().cycles() == 10);
  // First call: one 100 ms update; then nine early failures, each padded to a period.
  CHECK(rig.clock.now_us() == 10 * 100'000);
  CHECK(rig.exec.stats().missed_updates() == 9);
}

TEST_CASE("run_realtime: lingers after the end until teammates settle, or the linger time") {
  SUBCASE("teammate never settles: linger for the whole time") {
    Rig rig;
    rig.exec.abort("test abort");
    p3at::exec::RealtimeOptions options;
    options.linger_ms = 1000;
    const auto outcome = p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop, options);
    CHECK(outcome.phase == Phase::aborted);
    CHECK(rig.drive.calls == 10);  // 1 s of 100 ms cycles
    CHECK(rig.link.poll_calls == 10);
  }
  SUBCASE("teammate finished: return at once") {
    Rig rig;
    rig.link.set_teammate_status(p3at::hal::TeamStatus{"robot2", "finished", "idle", "", -1.0});
    rig.exec.abort("test abort");
    p3at::exec::RealtimeOptions options;
    options.linger_ms = 1000;
    (void)p3at::exec::run_realtime(rig.exec, rig.drive, rig.stop, options);
    CHECK(rig.drive.calls == 0);
  }
}
