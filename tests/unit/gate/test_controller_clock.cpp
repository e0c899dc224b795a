// The mission clock: the controller's SIP count × 100 ms, whatever the wall
// clock does, and wall time only while the controller has fallen silent.
#include <doctest/doctest.h>

#include "fake_clock.hpp"
#include "fake_drive_base.hpp"
#include "p3at/launch_gate/controller_clock.hpp"

using namespace p3at;

TEST_CASE("time is SIPs × period from the first reading, at any simulator speed-up") {
  test::FakeClock wall(7'000'000);
  test::FakeDriveBase drive;
  drive.step();
  drive.step();  // two SIPs before the mission: not mission time
  gate::ControllerClock clock(drive, wall);
  CHECK(clock.now_us() == 0);
  for (int i = 0; i < 10; ++i) {
    wall.advance_us(25'000);  // a 4× simulator: a SIP every 25 ms of wall time
    drive.step();
  }
  CHECK(clock.now_us() == 1'000'000);
  wall.advance_us(140'000);  // late, but not stalled
  CHECK(clock.now_us() == 1'000'000);
}

TEST_CASE("a silent controller: wall time beyond the stall allowance, never backwards") {
  test::FakeClock wall(0);
  test::FakeDriveBase drive;
  gate::ControllerClock clock(drive, wall);
  CHECK(clock.now_us() == 0);
  drive.step();
  CHECK(clock.now_us() == 100'000);
  wall.advance_us(1'150'000);  // 1.15 s without a SIP: 1.0 s beyond the 150 ms allowance
  CHECK(clock.now_us() == 1'100'000);
  drive.step();  // SIPs resume: controller time (200 ms) is behind; the clock holds
  CHECK(clock.now_us() == 1'100'000);
  for (int i = 0; i < 12; ++i) drive.step();
  CHECK(clock.now_us() == 1'400'000);
}

TEST_CASE("sleep_until_us waits the difference in wall time") {
  test::FakeClock wall(0);
  test::FakeDriveBase drive;
  gate::ControllerClock clock(drive, wall);
  clock.sleep_until_us(300'000);
  CHECK(wall.now_us() == 300'000);
  clock.sleep_until_us(-5);  // past: returns at once
  CHECK(wall.now_us() == 300'000);
}
