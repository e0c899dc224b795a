// team_peer: a stand-in robot on the team link, for hardware-in-the-loop tests.
//   team_peer run --url U --mission M --name alpha --roster alpha,bravo --key team.key
//                 [--notify at_door --to bravo] [--phase running] [--duration-s 30]
//                 [--verdict GO --hash HEX]
//       Opens the real LcmTeamLink, publishes telemetry and status (and, with
//       --verdict, a launch-gate verdict for mission hash --hash) every
//       --publish-ms, optionally notifies once, and logs what happens:
//       `[team_peer] event=ready|notified|acknowledged|status|stats ...`.
//   team_peer inject --url U --channel P3AT_NOTIFY --hex BYTES
//       An intruder without the key (and without LCM): sends one raw LCM
//       small-message datagram (docs/team-link.md) to the multicast group.

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cctype>
#include <optional>
#include <random>
#include <cstdio>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "p3at/hal/clock.hpp"
#include "p3at/hal/lcm_team_link.hpp"
#include "p3at/hal/team_key.hpp"
#include "p3at/hal/url.hpp"

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::string stats_line(const p3at::hal::TeamLinkStats& s) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "sent=%llu retransmissions=%llu accepted=%llu acks_received=%llu rejected_unknown_sender=%llu "
                "rejected_bad_tag=%llu rejected_replay=%llu rejected_other_mission=%llu malformed=%llu",
                static_cast<unsigned long long>(s.sent), static_cast<unsigned long long>(s.retransmissions),
                static_cast<unsigned long long>(s.accepted), static_cast<unsigned long long>(s.acks_received),
                static_cast<unsigned long long>(s.rejected_unknown_sender),
                static_cast<unsigned long long>(s.rejected_bad_tag), static_cast<unsigned long long>(s.rejected_replay),
                static_cast<unsigned long long>(s.rejected_other_mission), static_cast<unsigned long long>(s.malformed));
  return buf;
}

struct RunOptions {
  std::string url{p3at::hal::kDefaultTeamLcmUrl};
  std::string mission;
  std::string name;
  std::string roster;
  std::string key_path;
  std::string notify;
  std::string to;
  std::string phase = "running";
  std::string verdict;  ///< empty: publish no gate verdict
  std::string hash;
  double duration_s = 30.0;
  int publish_ms = 100;
};

int run(const RunOptions& o) {
  auto key = p3at::hal::load_team_key(o.key_path);
  if (!key) {
    std::fprintf(stderr, "team_peer: %s\n", key.error().message.c_str());
    return 1;
  }
  p3at::hal::TeamLinkConfig config;
  config.mission_id = o.mission;
  config.self = o.name;
  config.roster = split_commas(o.roster);
  auto opened = p3at::hal::open_lcm_team_link(o.url, config, key.value());
  if (!opened) {
    std::fprintf(stderr, "team_peer: %s\n", opened.error().message.c_str());
    return 1;
  }
  auto& link = *opened.value();
  std::printf("[team_peer] event=ready name=%s url=%s key=%s\n", o.name.c_str(), o.url.c_str(),
              p3at::hal::team_key_fingerprint(key.value()).c_str());
  std::fflush(stdout);

  std::optional<p3at::hal::GateVerdict> verdict;
  if (!o.verdict.empty()) {
    const auto decision = p3at::hal::gate_decision_from_string(o.verdict);
    if (!decision) {
      std::fprintf(stderr, "team_peer: --verdict must be GO, NO-GO or OVERRIDE\n");
      return 1;
    }
    verdict = p3at::hal::GateVerdict{o.name, o.hash, *decision, 0.99, 0.99, 0.99, 0.8, 60.0, 0.5, "team_peer", {}, {}, {}};
    // A fresh nonce, as a real robot's gate draws one (a test tool: std::random_device is enough).
    std::random_device rd;
    char hex[33];
    for (int i = 0; i < 16; ++i) std::snprintf(hex + 2 * i, 3, "%02x", rd() & 0xffu);
    verdict->nonce = std::string(hex, 32);
  }

  p3at::hal::SteadyClock clock;
  const std::int64_t start_us = clock.now_us();
  const auto end_us = start_us + static_cast<std::int64_t>(o.duration_s * 1e6);
  std::int64_t next_publish_us = start_us;
  std::uint64_t pending_seq = 0;  // 0: nothing waiting for acknowledgement
  if (!o.notify.empty()) {
    auto seq = link.notify(o.notify, split_commas(o.to));
    if (!seq) {
      std::fprintf(stderr, "team_peer: %s\n", seq.error().message.c_str());
      return 1;
    }
    pending_seq = seq.value();
    std::printf("[team_peer] event=notify message=%s seq=%llu\n", o.notify.c_str(),
                static_cast<unsigned long long>(seq.value()));
  }
  std::string last_stats;
  std::vector<std::string> last_status;
  std::vector<p3at::hal::TeamNotification> got;
  std::uint64_t cycles = 0;
  while (!g_stop && clock.now_us() < end_us) {
    const std::int64_t now = clock.now_us();
    got.clear();
    if (auto s = link.poll(now, got); !s) std::printf("[team_peer] event=error what=\"%s\"\n", s.error().message.c_str());
    for (const auto& n : got) {
      std::printf("[team_peer] event=notified sender=%s message=%s seq=%llu\n", n.sender.c_str(), n.message.c_str(),
                  static_cast<unsigned long long>(n.seq));
    }
    if (pending_seq != 0 && link.acknowledged(pending_seq)) {
      std::printf("[team_peer] event=acknowledged message=%s seq=%llu\n", o.notify.c_str(),
                  static_cast<unsigned long long>(pending_seq));
      pending_seq = 0;
    }
    std::vector<std::string> status;
    for (const auto& s : link.teammate_status()) status.push_back(s.robot + " phase=" + s.phase + " state=" + s.state);
    if (status != last_status) {
      for (const auto& s : status) std::printf("[team_peer] event=status robot=%s\n", s.c_str());
      last_status = status;
    }
    if (now >= next_publish_us) {
      ++cycles;
      p3at::hal::Telemetry t;
      t.state = "Waiting";
      t.x_m = 0.01 * static_cast<double>(cycles);
      t.cycles = cycles;
      (void)link.publish_telemetry(t);
      (void)link.publish_status({o.name, o.phase, "Waiting", "", 0.9});
      if (verdict) {
        if (auto st = link.publish_verdict(*verdict); !st) {
          std::printf("[team_peer] event=error what=\"%s\"\n", st.error().message.c_str());
        }
      }
      next_publish_us = now + o.publish_ms * 1000;
    }
    const std::string stats = stats_line(link.stats());
    if (stats != last_stats) {
      std::printf("[team_peer] event=stats %s\n", stats.c_str());
      last_stats = stats;
    }
    std::fflush(stdout);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::printf("[team_peer] event=exit %s\n", stats_line(link.stats()).c_str());
  std::fflush(stdout);
  return 0;
}

int inject(const std::string& url_text, const std::string& channel, const std::string& hex) {
  auto url = p3at::hal::parse_url(url_text);
  if (!url || url->scheme != "udpm" || url->port <= 0) {
    std::fprintf(stderr, "team_peer: expected udpm://GROUP:PORT, got '%s'\n", url_text.c_str());
    return 1;
  }
  const bool all_hex = std::all_of(hex.begin(), hex.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; });
  if (hex.size() % 2 != 0 || !all_hex) {
    std::fprintf(stderr, "team_peer: --hex needs an even number of hexadecimal digits\n");
    return 1;
  }
  // LCM small message: magic "LC02", a sequence number, the channel and its NUL, the payload.
  std::vector<std::uint8_t> packet{'L', 'C', '0', '2', 0, 0, 0, 1};
  packet.insert(packet.end(), channel.begin(), channel.end());
  packet.push_back(0);
  for (std::size_t i = 0; i < hex.size(); i += 2) {
    packet.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) {
    std::perror("team_peer: socket");
    return 1;
  }
  const unsigned char ttl = 0;
  ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(url->port));
  if (::inet_pton(AF_INET, url->host.c_str(), &to.sin_addr) != 1) {
    std::fprintf(stderr, "team_peer: bad multicast group '%s'\n", url->host.c_str());
    ::close(fd);
    return 1;
  }
  const ssize_t n = ::sendto(fd, packet.data(), packet.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(fd);
  if (n != static_cast<ssize_t>(packet.size())) {
    std::perror("team_peer: sendto");
    return 1;
  }
  std::printf("[team_peer] event=injected channel=%s bytes=%zu\n", channel.c_str(), packet.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"A stand-in robot (or intruder) on the team link, for hardware-in-the-loop tests."};
  app.require_subcommand(1);
  RunOptions o;
  auto* run_cmd = app.add_subcommand("run", "Run a team member on a real LcmTeamLink");
  run_cmd->add_option("--url", o.url, "LCM URL");
  run_cmd->add_option("--mission", o.mission, "Mission id")->required();
  run_cmd->add_option("--name", o.name, "This robot's name")->required();
  run_cmd->add_option("--roster", o.roster, "Team, comma-separated (self included)")->required();
  run_cmd->add_option("--key", o.key_path, "Team key file")->required();
  run_cmd->add_option("--notify", o.notify, "Message to notify once at start");
  run_cmd->add_option("--to", o.to, "Recipients of --notify, comma-separated");
  run_cmd->add_option("--phase", o.phase, "Phase in the published status");
  run_cmd->add_option("--verdict", o.verdict, "Publish a launch-gate verdict: GO, NO-GO or OVERRIDE");
  run_cmd->add_option("--hash", o.hash, "The verdict's mission hash (64 lowercase hex digits)");
  run_cmd->add_option("--duration-s", o.duration_s, "Run time before exiting (SIGTERM stops earlier)");
  run_cmd->add_option("--publish-ms", o.publish_ms, "Telemetry and status period")->check(CLI::Range(1, 60000));

  std::string url;
  std::string channel;
  std::string hex;
  auto* inject_cmd = app.add_subcommand("inject", "Send one raw datagram on a channel (no key, no LCM library)");
  inject_cmd->add_option("--url", url, "udpm://GROUP:PORT")->required();
  inject_cmd->add_option("--channel", channel, "LCM channel")->required();
  inject_cmd->add_option("--hex", hex, "Payload as hex")->required();
  CLI11_PARSE(app, argc, argv);

  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  if (*run_cmd) return run(o);
  return inject(url, channel, hex);
}
