#pragma once
// What the whole-mission hardware-in-the-loop tests share: team keys, two
// consecutive free ports for p3at_sim's two robots, a fresh LCM URL, the
// simulator's ground truth (final positions, motion commands received) and
// mission_exec's command line.

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "child_process.hpp"

namespace p3at::test {

inline const std::string kRelayMission = std::string(P3AT_SOURCE_DIR) + "/examples/relay/mission.yaml";
inline const std::string kRelayWorld = std::string(P3AT_SOURCE_DIR) + "/examples/relay/world.yaml";
inline const std::string kRelayModels = std::string(P3AT_SOURCE_DIR) + "/tests/sitl/data/relay_models.yaml";

/// A new team key file (p3at_team_key).
inline std::string make_key(const std::string& stem) {
  const std::string path = scratch_path(stem);
  ChildProcess tool({P3AT_TEAM_KEY_BIN, path}, path + ".log");
  REQUIRE(tool.wait_exit(10.0) == 0);
  return path;
}

/// Two consecutive free ports for robot1 and robot2.
inline int free_port_pair() {
  for (int attempt = 0; attempt < 50; ++attempt) {
    const int p = free_tcp_port();
    if (p >= 65535) continue;
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = htons(static_cast<std::uint16_t>(p + 1));
    const bool free = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    ::close(fd);
    if (free) return p;
  }
  FAIL("no free port pair");
  return 0;
}

/// A multicast URL on the loopback (ttl=0) with a port no other test uses now.
inline std::string fresh_lcm_url() {
  return "udpm://239.255.76.67:" + std::to_string(free_tcp_port()) + "?ttl=0";
}

/// One robot's rows of the simulator's truth CSV
/// (time_s,robot,true_x_m,true_y_m,...,motion_commands).
struct TruthRow {
  double time_s = 0, x_m = std::numeric_limits<double>::quiet_NaN(), y_m = std::numeric_limits<double>::quiet_NaN();
  unsigned long long motion_commands = 0;
};
inline std::vector<TruthRow> truth_rows(const std::string& csv, const std::string& robot) {
  std::ifstream in(csv);
  std::string line;
  std::vector<TruthRow> rows;
  while (std::getline(in, line)) {
    TruthRow r;
    char name[64] = {};
    double skip[7] = {};
    if (std::sscanf(line.c_str(), "%lf,%63[^,],%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%llu", &r.time_s, name, &r.x_m, &r.y_m,
                    &skip[0], &skip[1], &skip[2], &skip[3], &skip[4], &skip[5], &r.motion_commands) == 11 &&
        robot == name) {
      rows.push_back(r);
    }
  }
  return rows;
}

/// The last true position of `robot`.
inline std::pair<double, double> final_truth(const std::string& csv, const std::string& robot) {
  const auto rows = truth_rows(csv, robot);
  if (rows.empty()) return {NAN, NAN};
  return {rows.back().x_m, rows.back().y_m};
}

/// The motion commands `robot` had received by the simulator's last cycle;
/// -1 when the CSV holds no row for it (the simulator did not run).
inline long long motion_commands(const std::string& csv, const std::string& robot) {
  const auto rows = truth_rows(csv, robot);
  if (rows.empty()) return -1;
  return static_cast<long long>(rows.back().motion_commands);
}

/// mission_exec for `robot` against p3at_sim's port, with the team's key and LCM URL.
inline std::vector<std::string> exec_args(const std::string& robot, int port, const std::string& lcm,
                                          const std::string& key, const std::string& mission = kRelayMission,
                                          std::vector<std::string> extra = {}) {
  std::vector<std::string> args{P3AT_MISSION_EXEC_BIN, "--robot", robot, "--mission", mission, "--hal",
                                "tcp://127.0.0.1:" + std::to_string(port), "--lcm", lcm, "--team-key", key,
                                "--linger-s", "3"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

inline bool contains(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

}  // namespace p3at::test
