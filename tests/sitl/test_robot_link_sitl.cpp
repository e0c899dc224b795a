// Hardware-in-the-loop: the real bridge and p3at_ctl against p3at_sim running
// as a separate process, over real TCP on the loopback.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <thread>

#include "child_process.hpp"
#include "p3at/bridge/arcos_client.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/hal/tcp_listener.hpp"
#include "p3at/protocols/arcos/commands.hpp"
#include "p3at/protocols/arcos/decoder.hpp"
#include "p3at/protocols/arcos/sip.hpp"
#include "sim_fixture.hpp"

using namespace p3at;
using arcos::Command;

namespace {

std::unique_ptr<bridge::ArcosClient> make_client(const std::string& url, hal::Clock& clock, int reconnect_ms = 1000) {
  bridge::ClientConfig config;
  config.log_name = "sitl-bridge";
  config.reconnect_interval_ms = reconnect_ms;
  return std::make_unique<bridge::ArcosClient>([url] { return hal::open_byte_stream(url); }, clock, config);
}

// Waits for SIPs for `seconds` of wall time.
void cycle_for(bridge::ArcosClient& client, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) (void)client.wait_for_update(200);
}

// A bare ARCOS session, written directly with the codec: lets a test stop
// sending (to trip the watchdog), which the bridge's keep-alive never does.
struct RawSession {
  std::unique_ptr<hal::ByteStream> stream;
  arcos::PacketDecoder decoder;
  hal::SteadyClock clock;
  std::vector<arcos::Sip> sips;

  void send(const arcos::Frame& f) { REQUIRE(stream->write_all(f.span()).ok()); }
  // Reads for `seconds`, collecting SIPs; returns the packet ids seen.
  std::vector<std::uint8_t> read_for(double seconds) {
    std::vector<std::uint8_t> ids;
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    std::array<std::uint8_t, 512> buf{};
    while (std::chrono::steady_clock::now() < until) {
      auto got = stream->read_some(buf, 20);
      REQUIRE(got.ok());
      decoder.feed(std::span<const std::uint8_t>(buf.data(), got.value()), clock.now_us(), [&](const arcos::Packet& p) {
        ids.push_back(p.id);
        if (p.id == arcos::kSipMoving || p.id == arcos::kSipStopped) {
          auto sip = arcos::decode_sip(p);
          REQUIRE(sip.ok());
          sips.push_back(sip.value());
        }
      });
    }
    return ids;
  }
  void open_and_enable() {
    send(arcos::encode_command(arcos::kSync0));
    send(arcos::encode_command(arcos::kSync1));
    send(arcos::encode_command(arcos::kSync2));
    const auto ids = read_for(0.3);
    REQUIRE(ids.size() >= 3);
    send(arcos::encode_command(Command::open, 1));
    send(arcos::encode_command(Command::enable, 1));
  }
};

}  // namespace

TEST_CASE("drive 1 m at 300 mm/s over TCP and see about 1 m of odometry and of true motion") {
  test::SimProcess sim;
  REQUIRE(sim.ready());
  hal::SteadyClock clock;
  auto client = make_client(sim.url(), clock);
  REQUIRE(client->connect().ok());
  CHECK(client->info().identity.robot_class == "Pioneer");
  REQUIRE(client->info().config.has_value());
  cycle_for(*client, 0.3);
  const hal::Pose2 start = client->state().odometry;
  // Command 300 mm/s until odometry says we will coast to 1 m at 0.6 m/s² deceleration.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (client->state().odometry.x_m - start.x_m < 1.0 - 0.3 * 0.3 / (2 * 0.6)) {
    REQUIRE(client->set_velocity(0.3, 0.0).ok());
    (void)client->wait_for_update(200);
    REQUIRE(std::chrono::steady_clock::now() < give_up);
  }
  CHECK(client->state().trans_vel_mps == doctest::Approx(0.3).epsilon(0.1));
  REQUIRE(client->stop().ok());
  cycle_for(*client, 1.0);
  const double travelled = client->state().odometry.x_m - start.x_m;
  CHECK(travelled == doctest::Approx(1.0).epsilon(0.05));
  CHECK(std::fabs(client->state().trans_vel_mps) < 0.01);
  REQUIRE(client->disconnect().ok());
  // The simulator's ground truth: the robot really moved about 1 m.
  const std::string truth = test::read_file(sim.truth_path);
  REQUIRE(truth.find("true_x_m") != std::string::npos);
  const auto last_line_start = truth.rfind('\n', truth.size() - 2);
  double t = 0, x = 0;
  char name[64] = {};
  REQUIRE(std::sscanf(truth.c_str() + last_line_start + 1, "%lf,%63[^,],%lf", &t, name, &x) == 3);
  CHECK(std::fabs(x) == doctest::Approx(1.0).epsilon(0.1));
}

TEST_CASE("the firmware watchdog stops the robot 2 s after commands cease, and it resumes") {
  test::SimProcess sim({"--speedup", "4"});
  REQUIRE(sim.ready());
  RawSession raw;
  auto opened = hal::open_byte_stream(sim.url());
  REQUIRE(opened.ok());
  raw.stream = std::move(opened).value();
  raw.open_and_enable();
  raw.send(arcos::encode_command(Command::vel, 300));
  raw.read_for(0.4);  // 1.6 s simulated: moving
  REQUIRE_FALSE(raw.sips.empty());
  CHECK(raw.sips.back().moving);
  CHECK(raw.sips.back().left_vel > 200);
  raw.sips.clear();
  raw.read_for(1.2);  // 4.8 s simulated with no command: the watchdog has tripped
  REQUIRE_FALSE(raw.sips.empty());
  CHECK_FALSE(raw.sips.back().moving);
  CHECK(raw.sips.back().left_vel == 0);
  raw.send(arcos::encode_command(Command::vel, 300));  // commands return
  raw.sips.clear();
  raw.read_for(0.5);
  REQUIRE_FALSE(raw.sips.empty());
  CHECK(raw.sips.back().left_vel > 200);
  raw.send(arcos::encode_command(Command::close, 1));
}

TEST_CASE("link loss when the simulator is killed; reconnect when it returns") {
  hal::SteadyClock clock;
  auto sim = std::make_unique<test::SimProcess>();
  const int port = sim->port;
  REQUIRE(sim->ready());
  auto client = make_client(sim->url(), clock, 300);
  REQUIRE(client->connect().ok());
  cycle_for(*client, 0.3);
  REQUIRE(client->state().link == hal::LinkState::ok);
  sim->process.signal(SIGKILL);
  REQUIRE(sim->process.wait_exit(5.0) == 128 + SIGKILL);
  cycle_for(*client, 1.5);
  CHECK(client->state().link == hal::LinkState::link_lost);
  CHECK_FALSE(client->state().why_stopped.empty());
  CHECK_FALSE(client->set_velocity(0.2, 0.0).ok());
  sim.reset();
  test::SimProcess again({}, port);
  REQUIRE(again.ready());
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(8);
  while (client->state().link != hal::LinkState::ok && std::chrono::steady_clock::now() < give_up) {
    (void)client->wait_for_update(200);
  }
  CHECK(client->state().link == hal::LinkState::ok);
  CHECK(client->stats().reconnects == 1);
  CHECK(client->set_velocity(0.1, 0.0).ok());
  REQUIRE(client->disconnect().ok());
}

TEST_CASE("garbage injected into the simulator's stream is survived and counted by the bridge") {
  test::SimProcess sim;
  REQUIRE(sim.ready());
  // A proxy between bridge and simulator that corrupts the robot→client direction.
  auto listener = hal::TcpListener::listen("127.0.0.1", 0);
  REQUIRE(listener.ok());
  const int proxy_port = listener.value()->port();
  std::atomic<bool> stop{false};
  std::atomic<int> injected{0};
  std::thread proxy([&] {
    std::unique_ptr<hal::ByteStream> down;
    while (!down && !stop) {
      auto a = listener.value()->accept(50);
      if (a.ok()) down = std::move(a).value();
    }
    if (!down) return;
    auto up = hal::open_byte_stream(sim.url());
    if (!up.ok()) return;
    std::array<std::uint8_t, 1024> buf{};
    int chunk = 0;
    static constexpr std::uint8_t kJunk[] = {0xFA, 0x00, 0x13, 0xFA, 0xFB, 0x09, 0x32, 0x99, 0xFA, 0xFB, 0x02, 0x77};
    while (!stop) {
      auto from_client = down->read_some(buf, 5);
      if (!from_client.ok()) break;
      if (from_client.value() > 0 && !up.value()->write_all(std::span(buf.data(), from_client.value())).ok()) break;
      auto from_robot = up.value()->read_some(buf, 5);
      if (!from_robot.ok()) break;
      if (from_robot.value() > 0) {
        if (++chunk % 4 == 0) {
          (void)down->write_all(kJunk);
          ++injected;
        }
        if (!down->write_all(std::span(buf.data(), from_robot.value())).ok()) break;
      }
    }
  });
  hal::SteadyClock clock;
  auto client = make_client("tcp://127.0.0.1:" + std::to_string(proxy_port), clock);
  REQUIRE(client->connect().ok());
  cycle_for(*client, 2.0);
  CHECK(injected > 2);
  CHECK(client->decoder_stats().errors() + client->decoder_stats().discarded_bytes > 0);
  CHECK(client->stats().sips >= 12);
  CHECK(client->state().link == hal::LinkState::ok);
  REQUIRE(client->disconnect().ok());
  stop = true;
  proxy.join();
}

TEST_CASE("garbage sent to the simulator is counted and it keeps serving") {
  test::SimProcess sim;
  REQUIRE(sim.ready());
  {
    auto s = hal::open_byte_stream(sim.url());
    REQUIRE(s.ok());
    static constexpr std::uint8_t kJunk[] = {0x01, 0xFA, 0xFB, 0x03, 0x00, 0x13, 0x37, 0xFA, 0x42, 0xFF, 0xFA, 0xFB, 0xFF};
    REQUIRE(s.value()->write_all(kJunk).ok());
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  hal::SteadyClock clock;
  auto client = make_client(sim.url(), clock);
  REQUIRE(client->connect().ok());
  cycle_for(*client, 0.5);
  CHECK(client->state().link == hal::LinkState::ok);
  REQUIRE(client->disconnect().ok());
  sim.process.signal(SIGTERM);
  CHECK(sim.process.wait_exit(5.0) == 0);
  CHECK(sim.process.log().find("bad_packets=") != std::string::npos);
  CHECK(sim.process.log().find("bad_packets=0 ") == std::string::npos);
}

TEST_CASE("p3at_ctl: status and drive against the simulator; clear errors otherwise") {
  test::SimProcess sim;
  REQUIRE(sim.ready());
  {
    test::ChildProcess ctl({P3AT_CTL_BIN, sim.url(), "status"}, test::scratch_path("ctl-status.log"));
    REQUIRE(ctl.wait_exit(15.0) == 0);
    const std::string out = ctl.log();
    CHECK(out.find("class=Pioneer") != std::string::npos);
    CHECK(out.find("subclass=p3at") != std::string::npos);
    CHECK(out.find("trans_vel_max_mm_s=") != std::string::npos);
    CHECK(out.find("battery") != std::string::npos);
    CHECK(out.find("sonar_m") != std::string::npos);
    CHECK(out.find("motors=enabled") != std::string::npos);
  }
  {
    test::ChildProcess ctl({P3AT_CTL_BIN, sim.url(), "drive", "--vel", "300", "--secs", "1.5"},
                           test::scratch_path("ctl-drive.log"));
    REQUIRE(ctl.wait_exit(15.0) == 0);
    const std::string out = ctl.log();
    CHECK(out.find("x_m") != std::string::npos);
    // The last odometry line shows forward progress.
    const auto last = out.rfind('\n', out.size() - 2);
    double t = 0, x = -1;
    REQUIRE(std::sscanf(out.c_str() + last + 1, "%lf %lf", &t, &x) == 2);
    CHECK(x > 0.2);
    CHECK(x < 0.6);
  }
  {
    test::ChildProcess ctl({P3AT_CTL_BIN, "tcp://127.0.0.1:" + std::to_string(test::free_tcp_port()), "status"},
                           test::scratch_path("ctl-refused.log"));
    CHECK(ctl.wait_exit(15.0) == 1);
    CHECK(ctl.log().find("refused") != std::string::npos);
  }
  {
    test::ChildProcess ctl({P3AT_CTL_BIN, "bogus://x", "status"}, test::scratch_path("ctl-scheme.log"));
    CHECK(ctl.wait_exit(15.0) == 2);  // a malformed URL is bad input, as for every binary
    CHECK(ctl.log().find("unknown scheme") != std::string::npos);
  }
}

namespace {

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

}  // namespace

// The client's handshake resends (docs/hal.md, "Handshake resends") against the
// real simulator's fault knobs; about 2 s and 1.5 s of wall time.
TEST_CASE("p3at_sim loses the first OPEN and two ENABLEs: the bridge resends both and the robot drives") {
  test::SimProcess sim({"--drop-open", "1", "--drop-enable", "2"});
  REQUIRE(sim.ready());
  hal::SteadyClock clock;
  auto client = make_client(sim.url(), clock);
  REQUIRE(client->connect().ok());
  CHECK(client->state().link == hal::LinkState::ok);
  CHECK(client->state().motors_enabled);
  // At least the lost ones; one more only if the machine delays a SIP past the resend time.
  CHECK(client->stats().open_resends >= 1);
  CHECK(client->stats().open_resends <= 2);
  CHECK(client->stats().enable_resends >= 2);
  CHECK(client->stats().enable_resends <= 3);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (client->state().trans_vel_mps < 0.2 && std::chrono::steady_clock::now() < give_up) {
    REQUIRE(client->set_velocity(0.3, 0.0).ok());
    (void)client->wait_for_update(200);
  }
  CHECK(client->state().trans_vel_mps >= 0.2);
  REQUIRE(client->disconnect().ok());
  sim.process.signal(SIGTERM);
  REQUIRE(sim.process.wait_exit(5.0) == 0);
  const std::string log = sim.process.log();
  CHECK(count_of(log, "fault robot=robot1 dropped=OPEN") == 1);
  CHECK(count_of(log, "fault robot=robot1 dropped=ENABLE") == 2);
  CHECK(log.find("injected_drops=3") != std::string::npos);
  CHECK(log.find("motion_commands=0 ") == std::string::npos);
}

TEST_CASE("p3at_sim never honouring OPEN: the bridge gives up after 5 OPENs with a clear error, not a hang") {
  test::SimProcess sim({"--drop-open", "1000"});
  REQUIRE(sim.ready());
  hal::SteadyClock clock;
  auto client = make_client(sim.url(), clock);
  const auto start = std::chrono::steady_clock::now();
  const Status st = client->connect();
  const double waited_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().message.find("robot opened but sent no SIP (5 OPENs") != std::string::npos);
  CHECK(waited_s >= 1.5);
  CHECK(waited_s < 6.0);
  CHECK(client->stats().open_resends == 4);
  CHECK(client->state().link == hal::LinkState::disconnected);
  sim.process.signal(SIGTERM);
  REQUIRE(sim.process.wait_exit(5.0) == 0);
  CHECK(count_of(sim.process.log(), "dropped=OPEN") == 5);
}

// enable_motors() after connecting (re-enabling after a safety stop) against the
// real simulator losing the packets: the client resends and confirms from the
// SIPs. About 3 s of wall time: ~0.4 s per lost command (three 100 ms SIP
// cycles, then the resend and the SIP confirming it), the rest connecting and driving.
TEST_CASE("p3at_sim loses the ENABLE and the ENABLE 0 sent after connecting: the bridge resends each, the robot drives, then stops") {
  // p3at_sim drops the first N ENABLE 1 (ENABLE 0) it receives, whenever sent.
  test::SimProcess sim({"--drop-enable", "1", "--drop-disable", "1"});
  REQUIRE(sim.ready());
  hal::SteadyClock clock;
  bridge::ClientConfig config;
  config.log_name = "sitl-bridge";
  config.enable_motors = false;  // no ENABLE while connecting: the first one the simulator sees comes after
  bridge::ArcosClient client([url = sim.url()] { return hal::open_byte_stream(url); }, clock, config);
  REQUIRE(client.connect().ok());
  cycle_for(client, 0.3);
  REQUIRE_FALSE(client.state().motors_enabled);

  auto start = std::chrono::steady_clock::now();
  REQUIRE(client.enable_motors(true).ok());
  const double enable_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("enable_motors(true) with the first ENABLE lost returned after " << enable_s << " s");
  CHECK(client.state().motors_enabled);
  // At least the lost one; one more only if the machine delays a SIP past the resend.
  CHECK(client.stats().enable_resends >= 1);
  CHECK(client.stats().enable_resends <= 2);
  CHECK(enable_s >= 0.2);  // a resend needs three SIPs (100 ms apart) showing the motors off
  CHECK(enable_s < 1.6);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (client.state().trans_vel_mps < 0.2 && std::chrono::steady_clock::now() < give_up) {
    REQUIRE(client.set_velocity(0.3, 0.0).ok());
    (void)client.wait_for_update(200);
  }
  CHECK(client.state().trans_vel_mps >= 0.2);

  start = std::chrono::steady_clock::now();
  REQUIRE(client.enable_motors(false).ok());
  const double disable_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("enable_motors(false) with the first ENABLE 0 lost returned after " << disable_s << " s");
  CHECK_FALSE(client.state().motors_enabled);
  CHECK(client.stats().disable_resends >= 1);
  CHECK(client.stats().disable_resends <= 2);
  CHECK(client.stats().motor_switch_failures == 0);
  CHECK_FALSE(client.set_velocity(0.3, 0.0).ok());  // refused: the motors are off
  cycle_for(client, 0.3);
  CHECK(std::fabs(client.state().trans_vel_mps) < 0.01);
  REQUIRE(client.disconnect().ok());
  sim.process.signal(SIGTERM);
  REQUIRE(sim.process.wait_exit(5.0) == 0);
  const std::string log = sim.process.log();
  CHECK(count_of(log, "fault robot=robot1 dropped=ENABLE") == 1);
  CHECK(count_of(log, "fault robot=robot1 dropped=DISABLE") == 1);
  CHECK(log.find("injected_drops=2") != std::string::npos);
}
