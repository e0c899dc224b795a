// The ARCOS command watchdog: no command for 2000 ms of simulated time halts
// the robot; motion resumes when commands return.

#include <doctest/doctest.h>

#include "emulator_harness.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"

using namespace p3at::sim;
using p3at::arcos::Command;
using p3at::sim::test::any_log_contains;
using p3at::sim::test::EmulatorHarness;

TEST_CASE("the watchdog halts a silent client's robot after 2 s and motion resumes on the next command") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 300);
  h.cycle(19);  // 1.9 s without a further command: still driving
  const MotionController& c = h.fw.robot().controller();
  CHECK_FALSE(c.watchdog_halted());
  CHECK(c.trans_vel_mps() > 0.25);
  CHECK(h.fw.stats().watchdog_trips == 0);

  h.cycle(2);  // past 2.0 s
  CHECK(c.watchdog_halted());
  CHECK(h.fw.stats().watchdog_trips == 1);
  CHECK(any_log_contains(h.logs, "watchdog robot=robot1 state=tripped"));
  h.cycle(10);
  CHECK_FALSE(h.fw.robot().moving());
  CHECK(c.trans_vel_mps() == doctest::Approx(0.0));
  CHECK(h.fw.stats().watchdog_trips == 1);  // one trip, however long the silence

  // Any command, even a PULSE, brings the old motion back.
  h.send(Command::pulse);
  CHECK(any_log_contains(h.logs, "watchdog robot=robot1 state=resumed"));
  h.cycle(5);
  CHECK(h.fw.robot().moving());
  CHECK(c.trans_vel_mps() > 0.1);
}

TEST_CASE("a client that keeps talking never trips the watchdog") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 200);
  for (int i = 0; i < 20; ++i) {
    h.cycle(5);
    h.send(Command::pulse);  // ARIA's 500 ms keep-alive
  }
  CHECK(h.fw.stats().watchdog_trips == 0);
  CHECK(h.fw.robot().controller().trans_vel_mps() == doctest::Approx(0.2));
}

TEST_CASE("the controller's watchdog on its own") {
  MotionController c{MotionLimits{}};
  c.enable_motors(true);
  c.set_watchdog(true, 0, 2'000'000);
  c.command_trans_vel(0.3);
  for (std::int64_t t = 10'000; t <= 1'990'000; t += 10'000) c.step(t, 0.01, 0.0, 0.0);
  CHECK_FALSE(c.watchdog_halted());
  c.step(2'000'000, 0.01, 0.0, 0.0);
  CHECK(c.watchdog_halted());
  CHECK(c.stats().watchdog_trips == 1);
  c.note_command(2'000'000);
  CHECK_FALSE(c.watchdog_halted());
  c.set_watchdog(false, 2'000'000);
  for (std::int64_t t = 2'010'000; t <= 6'000'000; t += 10'000) c.step(t, 0.01, 0.0, 0.0);
  CHECK_FALSE(c.watchdog_halted());  // disarmed
}

TEST_CASE("the watchdog period is configurable and 0 turns it off") {
  EmulatorHarness h;
  h.fw.set_watchdog_ms(0);
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 300);
  h.cycle(50);
  CHECK(h.fw.stats().watchdog_trips == 0);
  CHECK(h.fw.robot().controller().trans_vel_mps() == doctest::Approx(0.3));

  EmulatorHarness fast;
  fast.fw.set_watchdog_ms(500);
  fast.open();
  fast.send(Command::config, 1);
  const auto cfg = p3at::arcos::decode_config(fast.receive().at(0));
  CHECK(cfg.watchdog_ms == 500);
  fast.send(Command::enable, 1);
  fast.send(Command::vel, 300);
  fast.cycle(6);
  CHECK(fast.fw.stats().watchdog_trips == 1);
}
