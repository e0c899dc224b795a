// The ARCOS robot side, driven byte for byte over an in-memory stream pair.

#include <doctest/doctest.h>

#include <cmath>

#include "emulator_harness.hpp"
#include "p3at/protocols/arcos/config_packet.hpp"

using namespace p3at::sim;
using p3at::arcos::Command;
using p3at::sim::test::any_log_contains;
using p3at::sim::test::EmulatorHarness;
using p3at::sim::test::exact_robot;
using p3at::sim::test::kDeg;
namespace arcos = p3at::arcos;

TEST_CASE("SYNC0/1/2 are each answered on their own, repeats included") {
  EmulatorHarness h;
  h.send(arcos::encode_command(arcos::kSync0));
  auto got = h.receive();
  REQUIRE(got.size() == 1);
  CHECK(got[0].id == 0);
  CHECK(got[0].payload_size == 0);

  h.send(arcos::encode_command(arcos::kSync0));  // a client that missed the reply asks again
  got = h.receive();
  REQUIRE(got.size() == 1);
  CHECK(got[0].id == 0);

  for (int repeat = 0; repeat < 2; ++repeat) {
    h.send(arcos::encode_command(arcos::kSync1));
    got = h.receive();
    REQUIRE(got.size() == 1);
    CHECK(got[0].id == 1);
  }
  for (int repeat = 0; repeat < 2; ++repeat) {
    h.send(arcos::encode_command(arcos::kSync2));
    got = h.receive();
    REQUIRE(got.size() == 1);
    CHECK(got[0].id == 2);
    const arcos::RobotIdentity id = arcos::decode_identity(got[0]);
    CHECK(id.name == "robot1");
    CHECK(id.robot_class == "Pioneer");
    CHECK(id.subclass == "p3at-sh");
  }
  CHECK_FALSE(h.fw.is_open());
  h.send(Command::open, 1);
  CHECK(h.fw.is_open());
  CHECK(any_log_contains(h.logs, "open robot=robot1"));
}

TEST_CASE("nothing is sent before SYNC0 and no SIP before OPEN") {
  EmulatorHarness h;
  // SYNC1 and SYNC2 out of turn, and other commands, get no answer.
  h.send(arcos::encode_command(arcos::kSync1));
  h.send(arcos::encode_command(arcos::kSync2));
  h.send(Command::enable, 1);
  h.cycle(5);
  CHECK(h.receive().empty());

  h.handshake();
  h.cycle(10);
  CHECK(h.receive().empty());  // synced but not open: silence
  CHECK(h.fw.stats().sips_sent == 0);

  h.send(Command::open, 1);
  h.cycle(10);
  const auto sips = h.receive_sips();
  CHECK(sips.size() == 10);  // one per 100 ms cycle
}

TEST_CASE("SIPs carry every optional group, ROTVEL and the controller time") {
  EmulatorHarness h;
  h.open();
  h.cycle(3);
  const auto sips = h.receive_sips();
  REQUIRE(sips.size() == 3);
  const arcos::Sip& s = sips.back();
  CHECK_FALSE(s.moving);
  CHECK(s.sonar_count == 16);
  CHECK(s.sonar[15].number == 15);
  CHECK(s.sonar[15].range == 5000);  // open world: maximum range
  REQUIRE(s.io.has_value());
  REQUIRE(s.battery_x10.has_value());
  CHECK(*s.battery_x10 == 130);
  REQUIRE(s.rotvel.has_value());
  CHECK(*s.rotvel == 0);
  REQUIRE(s.controller_time_us.has_value());
  CHECK(*s.controller_time_us == 300'000);
  REQUIRE(s.flags3.has_value());
  CHECK((s.flags & arcos::kFlagMotorsEnabled) == 0);

  h.send(Command::sonar, 0);
  h.cycle(1);
  const auto quiet = h.receive_sips();
  REQUIRE(quiet.size() == 1);
  CHECK(quiet[0].sonar_count == 0);
}

TEST_CASE("CONFIG is answered with non-zero current velocity maxima") {
  EmulatorHarness h;
  h.open();
  h.send(Command::config, 1);
  const auto got = h.receive();
  REQUIRE(got.size() == 1);
  REQUIRE(got[0].id == arcos::kConfigPacket);
  const arcos::ConfigPacket cfg = arcos::decode_config(got[0]);
  CHECK(cfg.robot_class == "Pioneer");
  CHECK(cfg.subclass == "p3at-sh");
  CHECK(cfg.name == "robot1");
  CHECK(cfg.trans_vel_max == 600);
  CHECK(cfg.rot_vel_max == 43);
  CHECK(cfg.trans_accel == 300);
  CHECK(cfg.trans_decel == 600);
  CHECK(cfg.sip_cycle_ms == 100);
  CHECK(cfg.watchdog_ms == 2000);

  h.send(Command::setv, 250);
  h.send(Command::setrv, 20);
  h.send(Command::config, 1);
  const arcos::ConfigPacket after = arcos::decode_config(h.receive().at(0));
  CHECK(after.trans_vel_max == 250);
  CHECK(after.rot_vel_max == 20);
  h.send(Command::setv, 0);  // ignored: a zero maximum would freeze ARIA
  h.send(Command::config, 1);
  CHECK(arcos::decode_config(h.receive().at(0)).trans_vel_max == 250);
}

TEST_CASE("ENABLE sets FLAGS bit 0 and ENABLE 0 clears it") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.cycle(1);
  auto sips = h.receive_sips();
  REQUIRE(sips.size() == 1);
  CHECK((sips[0].flags & arcos::kFlagMotorsEnabled) != 0);
  h.send(Command::enable, 0);
  h.cycle(1);
  sips = h.receive_sips();
  REQUIRE(sips.size() == 1);
  CHECK((sips[0].flags & arcos::kFlagMotorsEnabled) == 0);
}

TEST_CASE("VEL moves the robot; the SIPs show it moving and the odometry growing") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 300);
  h.drive(20);
  CHECK(h.fw.robot().true_pose().x_m > 0.35);
  const auto sips = h.receive_sips();
  REQUIRE(sips.size() == 20);
  CHECK(h.fw.stats().watchdog_trips == 0);
  const arcos::Sip& last = sips.back();
  CHECK(last.moving);
  CHECK(last.left_vel == 300);
  CHECK(last.right_vel == 300);
  CHECK(arcos::wrap_delta_15bit(0, last.xpos) == std::lround(1000.0 * h.fw.robot().odometry().x_m));
  CHECK(arcos::wrap_delta_15bit(sips.front().xpos, last.xpos) > 400);
  CHECK(h.fw.stats().motion_commands == 1);

  h.send(Command::stop);
  h.cycle(10);
  CHECK_FALSE(h.receive_sips().back().moving);
}

TEST_CASE("motion commands are counted only when they ask for motion, and disabled motors do not move") {
  EmulatorHarness h;
  h.open();
  h.send(Command::vel, 0);
  h.send(Command::rvel, 0);
  h.send(Command::head, 0);  // already there
  h.send(Command::pulse);
  CHECK(h.fw.stats().motion_commands == 0);
  h.send(Command::vel, 200);  // motors still disabled: received, but no motion
  h.cycle(10);
  CHECK(h.fw.stats().motion_commands == 1);
  CHECK_FALSE(h.fw.robot().moving());
  CHECK(h.fw.robot().true_pose().x_m == doctest::Approx(0.0));
  h.send(Command::rvel, -10);
  h.send(arcos::encode_vel2(-5, 5));
  h.send(Command::move, 100);
  h.send(Command::dhead, 30);
  h.send(Command::head, 45);
  h.send(Command::rotate, 5);
  CHECK(h.fw.stats().motion_commands == 7);
}

TEST_CASE("HEAD accepts negative headings, DHEAD turns relative, MOVE travels a distance") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::head, -90);
  h.drive(60);
  CHECK(h.fw.robot().odometry().theta_rad == doctest::Approx(-90 * kDeg).epsilon(0.005));
  const auto sips = h.receive_sips();
  CHECK(sips.back().thpos == doctest::Approx(-1024).epsilon(0.01));
  CHECK(sips.back().control == -1024);  // the heading setpoint

  h.send(Command::dhead, 45);
  h.drive(40);
  CHECK(h.fw.robot().odometry().theta_rad == doctest::Approx(-45 * kDeg).epsilon(0.005));

  h.send(Command::move, 500);
  h.drive(50);
  const SimRobot& r = h.fw.robot();
  CHECK(std::hypot(r.odometry().x_m, r.odometry().y_m) == doctest::Approx(0.5).epsilon(0.005));
  CHECK_FALSE(r.moving());
}

TEST_CASE("VEL2 drives the wheels separately") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(arcos::encode_vel2(-5, 5));  // ±100 mm/s: a turn in place, counter-clockwise
  h.drive(20);
  const SimRobot& r = h.fw.robot();
  CHECK(r.left_wheel_mps() == doctest::Approx(-0.1).epsilon(1e-6));
  CHECK(r.right_wheel_mps() == doctest::Approx(0.1).epsilon(1e-6));
  CHECK(r.true_pose().theta_rad > 0.3);
  CHECK(std::hypot(r.true_pose().x_m, r.true_pose().y_m) < 1e-9);
}

TEST_CASE("SETO resets the odometry and ESTOP halts with the e-stop flag") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 300);
  h.drive(20);
  CHECK(h.fw.robot().odometry().x_m > 0.3);
  h.send(Command::seto);
  CHECK(h.fw.robot().odometry().x_m == doctest::Approx(0.0));
  h.send(Command::estop);
  h.cycle(1);
  const auto sips = h.receive_sips();
  CHECK((sips.back().flags & arcos::kFlagEstop) != 0);
  CHECK((sips.back().flags & arcos::kFlagMotorsEnabled) == 0);
  CHECK_FALSE(sips.back().moving);
  h.send(Command::enable, 1);
  h.cycle(1);
  CHECK((h.receive_sips().back().flags & arcos::kFlagEstop) == 0);
}

TEST_CASE("subclass p3at reports positions in DistConvFactor 0.465 units") {
  RobotConfig r = exact_robot();
  r.subclass = "p3at";
  EmulatorHarness h(r);
  h.send(arcos::encode_command(arcos::kSync0));
  h.send(arcos::encode_command(arcos::kSync1));
  h.send(arcos::encode_command(arcos::kSync2));
  const auto id = h.receive();
  REQUIRE(id.size() == 3);
  CHECK(arcos::decode_identity(id[2]).subclass == "p3at");
  h.send(Command::open, 1);
  h.send(Command::enable, 1);
  h.send(Command::move, 1000);
  h.drive(60);
  const auto sips = h.receive_sips();
  const int counts = arcos::wrap_delta_15bit(0, sips.back().xpos);
  CHECK(counts * 0.465 == doctest::Approx(1000.0).epsilon(0.005));
}

TEST_CASE("CLOSE stops the robot, drops the connection, and the next session works") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 300);
  h.cycle(10);
  REQUIRE(h.fw.robot().moving());
  h.send(Command::close, 1);
  CHECK_FALSE(h.fw.connected());
  CHECK(h.client->peer_closed());
  CHECK(any_log_contains(h.logs, "disconnect robot=robot1 reason=close-command"));
  h.cycle(1);
  CHECK_FALSE(h.fw.robot().moving());
  CHECK_FALSE(h.fw.robot().controller().motors_enabled());

  h.connect();
  CHECK(h.fw.stats().connections == 2);
  h.cycle(3);
  CHECK(h.receive().empty());  // a new session starts silent
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 200);
  h.cycle(10);
  CHECK(h.receive_sips().size() == 10);
  CHECK(h.fw.robot().moving());
}

TEST_CASE("a client that vanishes without CLOSE is dropped and the robot halts") {
  EmulatorHarness h;
  h.open();
  h.send(Command::enable, 1);
  h.send(Command::vel, 300);
  h.cycle(5);
  h.client->close();
  h.cycle(1);
  CHECK_FALSE(h.fw.connected());
  CHECK(any_log_contains(h.logs, "reason=peer-closed"));
  h.cycle(1);
  CHECK_FALSE(h.fw.robot().moving());
}

TEST_CASE("unknown commands and extra arguments are ignored") {
  EmulatorHarness h;
  h.open();
  const std::uint8_t payload[] = {0x3B, 0x10, 0x00, 0x01, 0x02};
  h.send(arcos::encode_frame(99, payload));
  h.send(arcos::encode_frame(200, {}));
  CHECK(h.fw.stats().unknown_commands == 2);
  CHECK(h.fw.is_open());
  // ENABLE with bytes after its integer argument still enables.
  const std::uint8_t enable_extra[] = {0x3B, 0x01, 0x00, 0x55, 0x66};
  h.send(arcos::encode_frame(static_cast<std::uint8_t>(Command::enable), enable_extra));
  CHECK(h.fw.robot().controller().motors_enabled());
  h.cycle(1);
  CHECK(h.receive_sips().size() == 1);
}

TEST_CASE("garbage bytes are counted and the stream resynchronises") {
  EmulatorHarness h;
  h.open();
  std::vector<std::uint8_t> junk = {0x00, 0x13, 0x37, 0xFA, 0x00, 0x42};
  const auto enable = arcos::encode_command(Command::enable, 1);
  junk.insert(junk.end(), enable.bytes.begin(), enable.bytes.begin() + static_cast<std::ptrdiff_t>(enable.size));
  h.send_raw(junk);
  CHECK(h.fw.stats().garbage_bytes > 0);
  CHECK(h.fw.stats().bad_packets >= 1);  // the 0xFA not followed by 0xFB
  CHECK(h.fw.robot().controller().motors_enabled());

  // A packet with a corrupted checksum is dropped and counted.
  auto vel = arcos::encode_command(Command::vel, 300);
  vel.bytes[vel.size - 1] ^= 0xFF;
  const auto bad_before = h.fw.stats().bad_packets;
  h.send(vel);
  CHECK(h.fw.stats().bad_packets == bad_before + 1);
  CHECK(h.fw.stats().motion_commands == 0);
}

TEST_CASE("commands split across reads and several in one read are all handled") {
  EmulatorHarness h;
  h.open();
  const auto enable = arcos::encode_command(Command::enable, 1);
  const auto vel = arcos::encode_command(Command::vel, 250);
  std::vector<std::uint8_t> both(enable.bytes.begin(), enable.bytes.begin() + static_cast<std::ptrdiff_t>(enable.size));
  both.insert(both.end(), vel.bytes.begin(), vel.bytes.begin() + 4);
  h.send_raw(both);
  CHECK(h.fw.robot().controller().motors_enabled());
  CHECK(h.fw.stats().motion_commands == 0);
  h.send_raw({vel.bytes.begin() + 4, vel.bytes.begin() + static_cast<std::ptrdiff_t>(vel.size)});
  CHECK(h.fw.stats().motion_commands == 1);
  CHECK(h.fw.stats().packets_received == 6);  // SYNC0, SYNC1, SYNC2, OPEN, ENABLE, VEL
}
