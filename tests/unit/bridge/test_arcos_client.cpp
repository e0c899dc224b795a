// The ARCOS client session against a robot scripted from the protocol reference.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "fake_clock.hpp"
#include "memory_stream.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "scripted_robot.hpp"

using namespace p3at;
using arcos::Command;

namespace {

constexpr std::uint8_t num(Command c) { return static_cast<std::uint8_t>(c); }

// A client wired to a scripted robot through in-memory streams. Each new
// connection gets a fresh pipe, like a new TCP session.
struct Rig {
  test::FakeClock clock;
  test::ScriptedRobot robot{clock};
  std::vector<std::unique_ptr<test::MemoryStream>> robot_ends;
  int opens = 0;
  bool refuse_connections = false;
  std::unique_ptr<bridge::ArcosClient> client;

  explicit Rig(bridge::ClientConfig config = {}) {
    config.log_name = "test-bridge";
    client = std::make_unique<bridge::ArcosClient>(
        [this]() -> Result<std::unique_ptr<hal::ByteStream>> {
          if (refuse_connections) return make_error(Error::Code::refused, "memory://robot: connection refused");
          ++opens;
          test::MemoryPipe pipe;
          auto client_end = pipe.make_a();
          robot_ends.push_back(pipe.make_b());
          robot.attach(robot_ends.back().get());
          // Whenever the client waits for input, time passes and the robot runs.
          client_end->on_idle = [this](int timeout_ms) {
            clock.advance_us(std::int64_t{std::clamp(timeout_ms, 1, 10)} * 1000);
            robot.run();
          };
          client_end->on_write = [this] { robot.run(); };
          return std::unique_ptr<hal::ByteStream>(std::move(client_end));
        },
        clock, config);
  }

  // Runs the client's cycle for `seconds` of fake time.
  void run_for(double seconds) {
    const std::int64_t until = clock.now_us() + static_cast<std::int64_t>(seconds * 1e6);
    while (clock.now_us() < until) (void)client->wait_for_update(150);
  }
};

// The times at which the robot received OPEN: command 1 after the last SYNC2 (before it, 1 is SYNC1).
std::vector<std::int64_t> open_times(const test::ScriptedRobot& robot) {
  std::size_t from = 0;
  for (std::size_t i = 0; i < robot.received.size(); ++i) {
    if (robot.received[i].number == arcos::kSync2) from = i + 1;
  }
  std::vector<std::int64_t> out;
  for (std::size_t i = from; i < robot.received.size(); ++i) {
    if (robot.received[i].number == num(Command::open)) out.push_back(robot.received[i].at_us);
  }
  return out;
}

std::vector<std::int64_t> enable_on_times(const test::ScriptedRobot& robot) {
  std::vector<std::int64_t> out;
  for (const auto& c : robot.received) {
    if (c.number == num(Command::enable) && c.value != 0) out.push_back(c.at_us);
  }
  return out;
}

// The times at which the robot received ENABLE `value` (1 or 0), from its `from`th command on.
std::vector<std::int64_t> enable_times(const test::ScriptedRobot& robot, int value, std::size_t from) {
  std::vector<std::int64_t> out;
  for (std::size_t i = from; i < robot.received.size(); ++i) {
    const auto& c = robot.received[i];
    if (c.number == num(Command::enable) && (c.value != 0) == (value != 0)) out.push_back(c.at_us);
  }
  return out;
}

double seconds_since(const test::FakeClock& clock, std::int64_t start_us) {
  return static_cast<double>(clock.now_us() - start_us) / 1e6;
}

}  // namespace

TEST_CASE("handshake: SYNC0/1/2, OPEN, CONFIG, ENABLE against a reference robot") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  CHECK(rig.client->state().link == hal::LinkState::ok);
  CHECK(rig.client->info().identity.name == "AMRISim");
  CHECK(rig.client->info().identity.robot_class == "Pioneer");
  CHECK(rig.client->info().identity.subclass == "p3at");
  CHECK(rig.client->info().params.dist_conv == doctest::Approx(0.465));
  REQUIRE(rig.client->info().config.has_value());
  CHECK(rig.client->info().config->trans_vel_max > 0);
  const auto cmds = rig.robot.command_numbers();
  REQUIRE(cmds.size() >= 6);
  CHECK(cmds[0] == arcos::kSync0);
  CHECK(cmds[1] == arcos::kSync1);
  CHECK(cmds[2] == arcos::kSync2);
  CHECK(cmds[3] == num(Command::open));
  CHECK(cmds[4] == num(Command::config));
  CHECK(std::find(cmds.begin(), cmds.end(), num(Command::enable)) != cmds.end());
  CHECK(rig.robot.enabled);
  CHECK(rig.client->stats().handshakes == 1);
}

TEST_CASE("CONFIG unanswered is tolerated, after repeating it") {
  Rig rig;
  rig.robot.answer_config = false;
  REQUIRE(rig.client->connect().ok());
  CHECK_FALSE(rig.client->info().config.has_value());
  const auto cmds = rig.robot.command_numbers();
  const auto configs = std::count(cmds.begin(), cmds.end(), num(Command::config));
  CHECK(configs >= 4);  // every 200 ms for 1 s
  CHECK(configs <= 6);
  CHECK(rig.client->state().link == hal::LinkState::ok);
}

TEST_CASE("a lost OPEN is resent 300 ms later when no SIP follows, and the session comes up") {
  Rig rig;
  rig.robot.opens_to_ignore = 2;
  REQUIRE(rig.client->connect().ok());
  CHECK(rig.client->state().link == hal::LinkState::ok);
  const auto opens = open_times(rig.robot);
  REQUIRE(opens.size() == 3);
  CHECK(opens[1] - opens[0] >= 300'000);
  CHECK(opens[1] - opens[0] <= 320'000);
  CHECK(opens[2] - opens[1] >= 300'000);
  CHECK(rig.client->stats().open_resends == 2);
  // CONFIG only once the robot is open: it answered, so none were wasted on a closed robot.
  REQUIRE(rig.client->info().config.has_value());
}

TEST_CASE("OPEN never answered by SIPs: five OPENs over 1.5 s, then a clear error, not a hang") {
  Rig rig;
  rig.robot.opens_to_ignore = 1000;
  const std::int64_t start = rig.clock.now_us();
  auto st = rig.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == Error::Code::timeout);
  CHECK(st.error().message.find("robot opened but sent no SIP") != std::string::npos);
  CHECK(st.error().message.find("5 OPENs") != std::string::npos);
  const auto opens = open_times(rig.robot);
  CHECK(opens.size() == 5);
  CHECK(rig.client->stats().open_resends == 4);
  const double waited_s = static_cast<double>(rig.clock.now_us() - start) / 1e6;
  CHECK(waited_s >= 1.5);
  CHECK(waited_s <= 1.8);
  CHECK(rig.client->state().link == hal::LinkState::disconnected);
  CHECK(rig.client->stats().handshake_failures == 1);
}

TEST_CASE("a lost ENABLE is resent when three SIPs after it show the motors off") {
  Rig rig;
  rig.robot.enables_to_ignore = 1;
  REQUIRE(rig.client->connect().ok());
  CHECK(rig.robot.enabled);
  CHECK(rig.client->state().motors_enabled);
  const auto enables = enable_on_times(rig.robot);
  REQUIRE(enables.size() == 2);
  // Three SIP cycles of 100 ms between them.
  CHECK(enables[1] - enables[0] >= 250'000);
  CHECK(enables[1] - enables[0] <= 400'000);
  CHECK(rig.client->stats().enable_resends == 1);
  REQUIRE(rig.client->set_velocity(0.2, 0.0).ok());
  rig.run_for(0.5);
  CHECK(rig.client->state().trans_vel_mps == doctest::Approx(0.2));
}

TEST_CASE("motors that stay off (e-stop pressed): five ENABLEs, then an error that names the e-stop") {
  Rig rig;
  rig.robot.estop_pressed = true;
  auto st = rig.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("motors stayed off after 5 ENABLE commands") != std::string::npos);
  CHECK(st.error().message.find("e-stop pressed") != std::string::npos);
  CHECK(enable_on_times(rig.robot).size() == 5);
  CHECK(rig.client->stats().enable_resends == 4);
  CHECK(rig.client->state().link == hal::LinkState::disconnected);

  Rig lossy;
  lossy.robot.enables_to_ignore = 1000;
  st = lossy.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("(ENABLE lost?)") != std::string::npos);
}

TEST_CASE("with enable_motors off the client neither sends nor waits for ENABLE") {
  bridge::ClientConfig config;
  config.enable_motors = false;
  Rig rig(config);
  REQUIRE(rig.client->connect().ok());
  CHECK(enable_on_times(rig.robot).empty());
  CHECK_FALSE(rig.client->state().motors_enabled);
  CHECK(rig.client->stats().enable_resends == 0);
}

TEST_CASE("a robot still open from an earlier client is closed and re-synced") {
  Rig rig;
  rig.robot.still_open_at_start = true;
  REQUIRE(rig.client->connect().ok());
  const auto cmds = rig.robot.command_numbers();
  CHECK(std::find(cmds.begin(), cmds.end(), num(Command::close)) != cmds.end());
  CHECK(rig.client->state().link == hal::LinkState::ok);
}

TEST_CASE("an unanswered SYNC0 is retried") {
  Rig rig;
  rig.robot.syncs_to_ignore = 2;
  REQUIRE(rig.client->connect().ok());
  const auto cmds = rig.robot.command_numbers();
  CHECK(std::count(cmds.begin(), cmds.end(), arcos::kSync0) >= 3);
}

TEST_CASE("no robot responding: a timeout error after the handshake limit, not a hang") {
  Rig rig;
  rig.robot.silent = true;
  const std::int64_t start = rig.clock.now_us();
  auto st = rig.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == Error::Code::timeout);
  CHECK(st.error().message.find("no robot responding") != std::string::npos);
  CHECK(st.error().message.find("nothing came back") != std::string::npos);
  const double waited_s = static_cast<double>(rig.clock.now_us() - start) / 1e6;
  CHECK(waited_s >= 5.9);
  CHECK(waited_s <= 7.5);
  CHECK(rig.client->state().link == hal::LinkState::disconnected);
  CHECK(rig.client->stats().handshake_failures == 1);
}

TEST_CASE("a failed handshake says what came back: garbage, or packets with bad checksums") {
  Rig garbage;
  garbage.robot.garbage_replies = true;
  auto st = garbage.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("garbage, no ARCOS packet") != std::string::npos);
  CHECK(st.error().message.find("nothing came back") == std::string::npos);

  Rig noisy;
  noisy.robot.corrupt_replies = true;
  st = noisy.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("packets with bad checksums") != std::string::npos);
}

TEST_CASE("refused connection is an error value naming the robot") {
  Rig rig;
  rig.refuse_connections = true;
  auto st = rig.client->connect();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == Error::Code::refused);
  CHECK(st.error().message.find("memory://robot") != std::string::npos);
}

TEST_CASE("velocity commands, odometry through the 15-bit wrap with DistConvFactor 0.465") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.5);
  const hal::Pose2 start = rig.client->state().odometry;
  REQUIRE(rig.client->set_velocity(0.3, 0.0).ok());
  rig.run_for(10.0);  // 3 m: 6450 raw units from 0x7F00 crosses the wrap
  REQUIRE(rig.client->stop().ok());
  rig.run_for(0.5);
  const hal::Pose2 end = rig.client->state().odometry;
  CHECK(end.x_m - start.x_m == doctest::Approx(3.0).epsilon(0.05));
  CHECK(std::fabs(end.y_m - start.y_m) < 0.01);
  CHECK(rig.robot.vel_mm_s == 0);
  // VEL carried 300 mm/s.
  bool saw_vel_300 = false;
  for (const auto& c : rig.robot.received) saw_vel_300 |= c.number == num(Command::vel) && c.value == 300;
  CHECK(saw_vel_300);
}

TEST_CASE("heading accumulates through turns, RVEL in deg/s, ROTVEL read back") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->set_velocity(0.0, 30.0 * 3.14159265358979323846 / 180.0).ok());
  rig.run_for(15.0);  // 450 degrees: through the ±180° wrap
  CHECK(rig.client->state().rot_vel_radps == doctest::Approx(30.0 * 3.14159265358979323846 / 180.0));
  const double turned_deg = rig.client->state().odometry.theta_rad * 180.0 / 3.14159265358979323846;
  CHECK(turned_deg == doctest::Approx(450.0).epsilon(0.03));
}

TEST_CASE("sonar, battery and flags reach the robot state") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.3);
  const auto& s = rig.client->state();
  CHECK(s.sonar_m[3] == doctest::Approx(1.234));
  CHECK(s.sonar_m[12] == doctest::Approx(4.0));
  CHECK(s.sonar_m[0] < 0);  // never reported
  CHECK(s.battery_v == doctest::Approx(13.0));
  CHECK(s.motors_enabled);
}

TEST_CASE("keep-alive: the robot never hears nothing for more than 500 ms") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  const std::size_t first = rig.robot.received.size();
  rig.run_for(5.0);
  REQUIRE(rig.robot.received.size() > first + 8);
  for (std::size_t i = first; i + 1 < rig.robot.received.size(); ++i) {
    const auto gap_ms = (rig.robot.received[i + 1].at_us - rig.robot.received[i].at_us) / 1000;
    CHECK(gap_ms <= 520);
  }
  CHECK(rig.client->stats().keepalives_sent >= 9);
  // Idle keep-alives are PULSEs.
  CHECK(rig.robot.received.back().number == num(Command::pulse));
}

TEST_CASE("keep-alive also every 5 SIPs, for simulators running faster than real time") {
  Rig rig;
  rig.robot.sip_period_us = 20'000;  // a 5x speed-up: the firmware's watchdog counts simulated time
  REQUIRE(rig.client->connect().ok());
  const std::size_t first = rig.robot.received.size();
  rig.run_for(2.0);
  // Every 5 SIPs = 100 ms of wall time = 500 ms of the robot's time.
  const auto sent = rig.robot.received.size() - first;
  CHECK(sent >= 17);
  CHECK(sent <= 22);
}

TEST_CASE("keep-alive repeats the velocity in force") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->set_velocity(0.2, 0.0).ok());
  const std::size_t first = rig.robot.received.size();
  rig.run_for(2.0);
  int vel_repeats = 0;
  for (std::size_t i = first; i < rig.robot.received.size(); ++i) {
    vel_repeats += rig.robot.received[i].number == num(Command::vel) && rig.robot.received[i].value == 200;
  }
  CHECK(vel_repeats >= 3);
}

TEST_CASE("motion_stale_sips: a velocity nobody asks for again is stopped once, not repeated; asking again resumes") {
  bridge::ClientConfig config;
  config.motion_stale_sips = 10;
  Rig rig(config);
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->set_velocity(0.2, 0.0).ok());
  const std::size_t first = rig.robot.received.size();
  rig.run_for(2.0);  // 2 s of SIPs, and no set_velocity(): a stalled caller
  int vel_repeats = 0, stops = 0;
  for (std::size_t i = first; i < rig.robot.received.size(); ++i) {
    vel_repeats += rig.robot.received[i].number == num(Command::vel) && rig.robot.received[i].value == 200;
    stops += rig.robot.received[i].number == num(Command::stop);
  }
  CHECK(vel_repeats <= 1);  // at most the keep-alive before the 10th SIP
  CHECK(stops == 1);
  CHECK(rig.client->stats().stale_motion_stops == 1);
  // The caller is back: its request goes out at once.
  const std::size_t before = rig.robot.received.size();
  REQUIRE(rig.client->set_velocity(0.2, 0.0).ok());
  REQUIRE(rig.robot.received.size() > before);
  CHECK(rig.robot.received[before].number == num(Command::vel));
}

TEST_CASE("link loss: no SIP for 1 s refuses motion; SIPs returning restore it") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.5);
  rig.robot.sips_paused = true;
  rig.run_for(1.5);
  CHECK(rig.client->state().link == hal::LinkState::link_lost);
  CHECK(rig.client->state().why_stopped.find("no SIP") != std::string::npos);
  auto refused = rig.client->set_velocity(0.3, 0.0);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().code == Error::Code::state);
  CHECK(rig.client->stats().refused_motion == 1);
  CHECK(rig.client->stats().link_losses == 1);
  rig.robot.sips_paused = false;
  rig.run_for(0.5);
  CHECK(rig.client->state().link == hal::LinkState::ok);
  CHECK(rig.client->set_velocity(0.3, 0.0).ok());
}

TEST_CASE("link loss when the stream closes, then automatic reconnect") {
  bridge::ClientConfig config;
  config.reconnect_interval_ms = 500;
  Rig rig(config);
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.3);
  rig.refuse_connections = true;
  rig.robot_ends.back()->close();  // the robot goes away
  rig.run_for(2.0);
  CHECK(rig.client->state().link == hal::LinkState::link_lost);
  CHECK_FALSE(rig.client->set_velocity(0.1, 0.0).ok());
  rig.refuse_connections = false;  // it comes back
  rig.run_for(2.0);
  CHECK(rig.client->state().link == hal::LinkState::ok);
  CHECK(rig.client->stats().reconnects == 1);
  CHECK(rig.opens == 2);
  CHECK(rig.client->set_velocity(0.1, 0.0).ok());
}

TEST_CASE("clean disconnect: ENABLE 0, at least 100 ms, then CLOSE") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.3);
  REQUIRE(rig.client->disconnect().ok());
  rig.robot.run();  // let the robot read what was sent last
  const auto& r = rig.robot.received;
  REQUIRE(r.size() >= 2);
  const auto& last = r[r.size() - 1];
  const auto& before = r[r.size() - 2];
  CHECK(before.number == num(Command::enable));
  CHECK(before.value == 0);
  CHECK(last.number == num(Command::close));
  CHECK(last.at_us - before.at_us >= 100'000);
  CHECK(rig.client->state().link == hal::LinkState::disconnected);
  CHECK_FALSE(rig.robot.opened);
  CHECK(rig.client->disconnect().ok());  // twice is harmless
}

TEST_CASE("emergency stop latches until motors are re-enabled") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->set_velocity(0.3, 0.0).ok());
  rig.run_for(0.5);
  REQUIRE(rig.client->emergency_stop().ok());
  rig.run_for(0.2);
  const auto cmds = rig.robot.command_numbers();
  CHECK(std::find(cmds.begin(), cmds.end(), num(Command::estop)) != cmds.end());
  CHECK_FALSE(rig.robot.enabled);
  CHECK_FALSE(rig.client->set_velocity(0.3, 0.0).ok());
  REQUIRE(rig.client->enable_motors(true).ok());
  rig.run_for(0.2);
  CHECK(rig.robot.enabled);
  CHECK(rig.client->set_velocity(0.3, 0.0).ok());
}

TEST_CASE("garbage in the stream is counted and survived") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.3);
  const std::uint8_t junk[] = {0x00, 0xFA, 0x11, 0xFA, 0xFB, 0x05, 0x32, 0x01, 0x02, 0xDE, 0xAD, 0x42};
  (void)rig.robot_ends.back()->write_all(junk);
  const auto sips_before = rig.client->stats().sips;
  rig.run_for(1.0);
  CHECK(rig.client->stats().sips >= sips_before + 8);
  CHECK(rig.client->decoder_stats().errors() >= 1);
  CHECK(rig.client->state().link == hal::LinkState::ok);
}

// enable_motors() after connecting: confirmed and resent like the connect-time
// ENABLE (docs/hal.md, "Handshake resends").
TEST_CASE("after connecting, a lost ENABLE is resent when three SIPs show the motors off, and confirmed") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  rig.run_for(0.3);
  REQUIRE(rig.client->emergency_stop().ok());  // a safety stop: ESTOP, ENABLE 0
  rig.run_for(0.3);
  REQUIRE_FALSE(rig.robot.enabled);
  rig.robot.enables_to_ignore = 1;  // the re-enable is lost on the line
  const std::size_t from = rig.robot.received.size();
  const std::int64_t start = rig.clock.now_us();
  REQUIRE(rig.client->enable_motors(true).ok());
  // Confirmed before it returned: the robot's motors are on and a SIP said so.
  CHECK(rig.robot.enabled);
  CHECK(rig.client->state().motors_enabled);
  const auto enables = enable_times(rig.robot, 1, from);
  REQUIRE(enables.size() == 2);
  CHECK(enables[1] - enables[0] >= 250'000);  // three SIP cycles of 100 ms
  CHECK(enables[1] - enables[0] <= 400'000);
  CHECK(seconds_since(rig.clock, start) <= 0.6);
  CHECK(rig.client->stats().enable_resends == 1);
  CHECK(rig.client->stats().motor_switch_failures == 0);
  REQUIRE(rig.client->set_velocity(0.2, 0.0).ok());
  rig.run_for(0.5);
  CHECK(rig.client->state().trans_vel_mps == doctest::Approx(0.2));
}

TEST_CASE("after connecting, an ENABLE never honoured: five ENABLEs, an error the caller sees, and motion refused") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->emergency_stop().ok());
  rig.run_for(0.3);
  rig.robot.enables_to_ignore = 1000;
  const std::size_t from = rig.robot.received.size();
  const std::int64_t start = rig.clock.now_us();
  const Status st = rig.client->enable_motors(true);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("motors stayed off after 5 ENABLE commands, 3 SIPs apart") != std::string::npos);
  CHECK(st.error().message.find("(ENABLE lost?)") != std::string::npos);
  CHECK(enable_times(rig.robot, 1, from).size() == 5);
  CHECK(seconds_since(rig.clock, start) >= 1.4);
  CHECK(seconds_since(rig.clock, start) <= 1.8);
  CHECK(rig.client->stats().enable_resends == 4);
  CHECK(rig.client->stats().motor_switch_failures == 1);
  // The link itself is fine; the motors are not, so nothing may look like driving.
  CHECK(rig.client->state().link == hal::LinkState::ok);
  const std::size_t before_motion = rig.robot.received.size();
  const Status refused = rig.client->set_velocity(0.3, 0.0);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().code == Error::Code::state);
  CHECK(refused.error().message.find("motors not enabled") != std::string::npos);
  CHECK(refused.error().message.find("ENABLE lost?") != std::string::npos);
  CHECK(rig.robot.received.size() == before_motion);  // no VEL went out
  // Later an ENABLE gets through: the refusal lifts.
  rig.robot.enables_to_ignore = 0;
  REQUIRE(rig.client->enable_motors(true).ok());
  REQUIRE(rig.client->set_velocity(0.3, 0.0).ok());
  rig.run_for(0.5);
  CHECK(rig.client->state().trans_vel_mps == doctest::Approx(0.3));

  // The robot's e-stop button pressed after connecting: the error says so.
  Rig pressed;
  REQUIRE(pressed.client->connect().ok());
  pressed.robot.estop_pressed = true;
  REQUIRE(pressed.client->emergency_stop().ok());
  const Status held = pressed.client->enable_motors(true);
  REQUIRE_FALSE(held.ok());
  CHECK(held.error().message.find("(the robot reports its e-stop pressed)") != std::string::npos);
  CHECK_FALSE(pressed.client->set_velocity(0.3, 0.0).ok());
}

TEST_CASE("a lost DISABLE is resent while SIPs show the motors on; motion is refused from the start") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->set_velocity(0.3, 0.0).ok());
  rig.run_for(0.5);
  rig.robot.disables_to_ignore = 2;
  const std::size_t from = rig.robot.received.size();
  REQUIRE(rig.client->enable_motors(false).ok());
  CHECK_FALSE(rig.robot.enabled);
  CHECK_FALSE(rig.client->state().motors_enabled);
  const auto disables = enable_times(rig.robot, 0, from);
  REQUIRE(disables.size() == 3);
  CHECK(disables[1] - disables[0] >= 250'000);
  CHECK(disables[2] - disables[1] >= 250'000);
  CHECK(rig.client->stats().disable_resends == 2);
  CHECK(rig.client->stats().motor_switch_failures == 0);
  const Status refused = rig.client->set_velocity(0.3, 0.0);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().message.find("motors disabled") != std::string::npos);
  // The keep-alive does not repeat the velocity that was in force.
  rig.run_for(1.0);
  for (std::size_t i = from; i < rig.robot.received.size(); ++i) {
    CHECK_FALSE((rig.robot.received[i].number == num(Command::vel) && rig.robot.received[i].value != 0));
  }
  REQUIRE(rig.client->enable_motors(true).ok());
  CHECK(rig.client->set_velocity(0.3, 0.0).ok());
}

TEST_CASE("a DISABLE never honoured: five ENABLE 0s, then ESTOP and an error the caller sees") {
  Rig rig;
  REQUIRE(rig.client->connect().ok());
  REQUIRE(rig.client->set_velocity(0.3, 0.0).ok());
  rig.run_for(0.5);
  rig.robot.disables_to_ignore = 1000;
  const std::size_t from = rig.robot.received.size();
  const Status st = rig.client->enable_motors(false);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("motors stayed ON after 5 ENABLE 0 commands, 3 SIPs apart") != std::string::npos);
  CHECK(st.error().message.find("DISABLE lost?") != std::string::npos);
  CHECK(enable_times(rig.robot, 0, from).size() == 5);
  CHECK(rig.client->stats().disable_resends == 4);
  CHECK(rig.client->stats().motor_switch_failures == 1);
  // The last resort went out after the fifth ENABLE 0, and the wheels halted.
  rig.robot.run();
  REQUIRE_FALSE(rig.robot.received.empty());
  CHECK(rig.robot.received.back().number == num(Command::estop));
  CHECK(rig.robot.enabled);  // still on: the caller was told
  CHECK(rig.robot.vel_mm_s == 0);
  CHECK_FALSE(rig.client->set_velocity(0.3, 0.0).ok());
}
