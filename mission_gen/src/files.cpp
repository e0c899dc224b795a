// Generated missions on disk, and the coverage table over many of them.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "gen_internal.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/common/text_columns.hpp"

namespace p3at::mission_gen {

void write_generated(const GeneratedMission& g, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create " + dir + ": " + ec.message());
  for (const auto& [name, text] : {std::pair{"mission.yaml", &g.mission_yaml}, std::pair{"world.yaml", &g.world_yaml}}) {
    const std::string path = dir + "/" + name;
    std::ofstream out(path, std::ios::binary);
    out << *text;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path);
  }
}

std::string coverage_table(const std::vector<Coverage>& missions) {
  std::map<std::size_t, std::size_t> team_sizes;
  std::size_t n = missions.size();
  const auto count = [&](auto pred) {
    return static_cast<std::size_t>(std::count_if(missions.begin(), missions.end(), pred));
  };
  double min_leg = 1e9, max_leg = 0, min_v = 1e9, max_v = 0, min_drop = 1e9, max_drop = 0, max_gain = 0;
  double min_rt = 1e9, max_rt = 0;
  for (const Coverage& c : missions) {
    ++team_sizes[c.robots];
    min_leg = std::min(min_leg, c.min_leg_m);
    max_leg = std::max(max_leg, c.max_leg_m);
    min_v = std::min(min_v, c.min_speed_mps);
    max_v = std::max(max_v, c.max_speed_mps);
    min_drop = std::min(min_drop, c.min_dropoff_m);
    max_drop = std::max(max_drop, c.max_dropoff_m);
    max_gain = std::max(max_gain, c.max_noise_gain);
    min_rt = std::min(min_rt, c.min_random_trans);
    max_rt = std::max(max_rt, c.max_random_trans);
  }
  // Built with the project's formatters (printf's conversions byte for byte),
  // not into a fixed buffer, so no row is ever cut.
  std::string s;
  const auto row = [&](const std::string& what, std::size_t k) {
    s += left_aligned(what, 52) + " " + right_aligned(std::to_string(k), 5) + " of " + std::to_string(n) + "\n";
  };
  for (const auto& [robots, k] : team_sizes) row(std::to_string(robots) + (robots == 1 ? " robot" : " robots"), k);
  s += "legs " + format_fixed(min_leg, 1) + " .. " + format_fixed(max_leg, 1) + " m, speeds " + format_fixed(min_v, 2) +
       " .. " + format_fixed(max_v, 2) + " m/s, dropoff " + format_fixed(min_drop, 2) + " .. " +
       format_fixed(max_drop, 2) + " m, noise gain <= " + format_fixed(max_gain, 3) + "\n";
  s += "random odometry error per unit " + format_fixed(min_rt, 4) + " .. " + format_fixed(max_rt, 4) + "\n";
  row("NOISE redrawn every cycle (persistence 1)", count([](const Coverage& c) { return c.noise_redrawn_every_cycle > 0; }));
  row("NOISE held for a whole leg", count([](const Coverage& c) { return c.noise_held_whole_leg > 0; }));
  row("Spin left by HasTurned", count([](const Coverage& c) { return c.spins > 0; }));
  row("HasTurned with an offset", count([](const Coverage& c) { return c.spin_offsets > 0; }));
  row("a loop (patrol back-edge)", count([](const Coverage& c) { return c.loops > 0; }));
  row("Notified leaving a GoToGuarded (recall mid-leg)", count([](const Coverage& c) { return c.notified_from_moving > 0; }));
  row("Notified leaving a Spin (recall mid-spin)", count([](const Coverage& c) { return c.notified_from_spin > 0; }));
  row("Notified leaving a Stop (a wait)", count([](const Coverage& c) { return c.notified_from_stop > 0; }));
  row("AtGoal racing Notified out of one state", count([](const Coverage& c) { return c.at_goal_racing_notified > 0; }));
  row("a message to several recipients", count([](const Coverage& c) { return c.multi_recipient_messages > 0; }));
  row("robots whose routes cross", count([](const Coverage& c) { return c.crossing_paths > 0; }));
  row("pillars", count([](const Coverage& c) { return c.world.pillars > 0; }));
  row("free-standing walls", count([](const Coverage& c) { return c.world.wall_stubs > 0; }));
  row("doorways", count([](const Coverage& c) { return c.world.doorways > 0; }));
  row("alcoves", count([](const Coverage& c) { return c.world.alcoves > 0; }));
  row("a robot with wheel-scale or track error", count([](const Coverage& c) { return c.systematic_error_robots > 0; }));
  row("a lossy radio", count([](const Coverage& c) { return c.lossy_radio; }));
  row("a slow radio (slow deliveries)", count([](const Coverage& c) { return c.slow_radio; }));
  return s;
}

}  // namespace p3at::mission_gen
