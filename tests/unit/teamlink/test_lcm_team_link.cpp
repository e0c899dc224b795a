// LcmTeamLink over real LCM UDP multicast on the loopback (ttl=0), in one
// process. The port is derived from the pid so parallel runs do not meet.
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/lcm_team_link.hpp"
#include "team_test_util.hpp"

using namespace p3at;

namespace {

std::string test_url() {
  return "udpm://239.255.76.67:" + std::to_string(30000 + ::getpid() % 20000) + "?ttl=0";
}

std::unique_ptr<hal::TeamLink> open(const std::string& self, std::uint8_t key_seed = 1) {
  auto link = hal::open_lcm_team_link(test_url(), test::team_config(self), test::fixed_key(key_seed));
  REQUIRE_MESSAGE(link.ok(), (link.ok() ? "" : link.error().message));
  return std::move(link.value());
}

struct Polled {
  std::vector<hal::TeamNotification> got;
};

// Polls every link every 5 ms of real time until `done` or `timeout_s`.
template <class Done>
bool poll_until(std::vector<std::pair<hal::TeamLink*, Polled*>> links, Done done, double timeout_s) {
  hal::SteadyClock clock;
  const auto deadline = clock.now_us() + static_cast<std::int64_t>(timeout_s * 1e6);
  while (clock.now_us() < deadline) {
    for (auto& [link, polled] : links) REQUIRE(link->poll(clock.now_us(), polled->got).ok());
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace

TEST_CASE("two LcmTeamLinks exchange an authenticated notification, ack and status over udpm") {
  auto alpha = open("alpha");
  auto bravo = open("bravo");
  Polled a;
  Polled b;
  REQUIRE(alpha->publish_status({"alpha", "running", "GoToDoor", "", 0.91}).ok());
  auto seq = alpha->notify("at_door", {"bravo"});
  REQUIRE(seq.ok());
  const bool done = poll_until({{alpha.get(), &a}, {bravo.get(), &b}},
                               [&] { return alpha->acknowledged(seq.value()) && !b.got.empty(); }, 10.0);
  REQUIRE(done);
  REQUIRE(b.got.size() == 1);
  CHECK(b.got[0].sender == "alpha");
  CHECK(b.got[0].message == "at_door");
  CHECK(b.got[0].seq == seq.value());
  CHECK(a.got.empty());
  CHECK(bravo->stats().accepted == 1);
  CHECK(alpha->stats().acks_received >= 1);

  // The status was sent before bravo polled for the first time; retransmit it
  // so the test does not depend on LCM's buffering of the first one.
  const bool status_seen = poll_until(
      {{alpha.get(), &a}, {bravo.get(), &b}},
      [&] {
        (void)alpha->publish_status({"alpha", "running", "GoToDoor", "", 0.91});
        return !bravo->teammate_status().empty();
      },
      5.0);
  REQUIRE(status_seen);
  CHECK(bravo->teammate_status()[0].robot == "alpha");
  CHECK(bravo->teammate_status()[0].p_success == doctest::Approx(0.91));

  // The sequence number is seeded from the wall clock (microseconds since the
  // epoch): a restart never reuses one.
  const auto wall_us = std::chrono::duration_cast<std::chrono::microseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
  CHECK(seq.value() <= static_cast<std::uint64_t>(wall_us));
  CHECK(seq.value() > static_cast<std::uint64_t>(wall_us) - 600'000'000ull);
}

TEST_CASE("a robot with the wrong key cannot fire a trigger or stop a teammate over udpm") {
  auto bravo = open("bravo");
  auto forger = open("alpha", 13);
  Polled b;
  Polled f;
  REQUIRE(forger->notify("abort", {"bravo"}).ok());
  const bool rejected = poll_until(
      {{bravo.get(), &b}, {forger.get(), &f}},
      [&] {
        (void)forger->publish_status({"alpha", "aborted", "", "forged", 0.0});
        return bravo->stats().rejected_bad_tag >= 3;
      },
      10.0);
  REQUIRE(rejected);
  CHECK(b.got.empty());
  CHECK(bravo->teammate_status().empty());
  CHECK(bravo->stats().accepted == 0);
  CHECK(forger->stats().acks_received == 0);
}

TEST_CASE("open_lcm_team_link errors are values naming the URL") {
  auto tcp = hal::open_lcm_team_link("tcp://127.0.0.1:1", test::team_config("alpha"), test::fixed_key());
  REQUIRE_FALSE(tcp.ok());
  CHECK(tcp.error().code == Error::Code::invalid_argument);
  CHECK(tcp.error().message.find("tcp://127.0.0.1:1") != std::string::npos);

  CHECK_FALSE(hal::open_lcm_team_link("not a url", test::team_config("alpha"), test::fixed_key()).ok());
  CHECK_FALSE(hal::open_lcm_team_link("", test::team_config("alpha"), test::fixed_key()).ok());

  auto bad_config = hal::open_lcm_team_link(test_url(), test::team_config("zulu"), test::fixed_key());
  REQUIRE_FALSE(bad_config.ok());
  CHECK(bad_config.error().message.find("roster") != std::string::npos);

  auto memq = hal::open_lcm_team_link("memq://", test::team_config("alpha"), test::fixed_key());
  REQUIRE(memq.ok());
  std::vector<hal::TeamNotification> got;
  REQUIRE(memq.value()->notify("x", {"bravo"}).ok());
  CHECK(memq.value()->poll(0, got).ok());
  CHECK(got.empty());  // its own message comes back and is ignored
  CHECK(memq.value()->stats().malformed == 0);
}
