// The mission generator: the same seed gives the same bytes; every mission
// of 500 seeds loads through the real loaders, from the files too; the ranges
// the issue asks for; and each feature of the format appears often enough
// over those 500 seeds (counted from the loaded missions, not the generator).

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "p3at/mission_gen/generator.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/sim/world_config.hpp"
#include "scratch.hpp"

using namespace p3at;

namespace {

mission_gen::GeneratedMission gen(std::uint64_t seed, std::size_t lo = 1, std::size_t hi = 6) {
  mission_gen::GenerateOptions o;
  o.seed = seed;
  o.min_robots = lo;
  o.max_robots = hi;
  return mission_gen::generate(o);
}

}  // namespace

TEST_CASE("generator: the same seed gives the same bytes, another seed another mission") {
  for (std::uint64_t s : {1ULL, 7ULL, 123456789ULL}) {
    const auto a = gen(s), b = gen(s);
    CHECK(a.mission_yaml == b.mission_yaml);
    CHECK(a.world_yaml == b.world_yaml);
    CHECK(a.name == "gen_" + std::to_string(s));
  }
  CHECK(gen(1).mission_yaml != gen(2).mission_yaml);
  CHECK(gen(1).world_yaml != gen(2).world_yaml);
}

TEST_CASE("generator: 500 seeds load, from text and from files, within the issue's ranges") {
  const std::filesystem::path dir = p3at::test::scratch_path("mission_gen");
  std::vector<mission_gen::Coverage> cov;
  std::vector<std::size_t> sizes(7, 0);
  for (std::uint64_t s = 1; s <= 500; ++s) {
    CAPTURE(s);
    mission_gen::GeneratedMission g;
    REQUIRE_NOTHROW(g = gen(s));
    // Written and read back by the loaders a user's files go through.
    if (s % 25 == 0) {
      const std::string d = (dir / g.name).string();
      mission_gen::write_generated(g, d);
      CHECK(mission::load_mission_file(d + "/mission.yaml") == g.mission);
      CHECK(sim::load_world_file(d + "/world.yaml").walls.size() == g.world.walls.size());
    }
    // Every mission robot has a world robot at the same start.
    REQUIRE(g.world.robots.size() == g.mission.robots.size());
    for (std::size_t i = 0; i < g.mission.robots.size(); ++i) {
      CHECK(g.world.robots[i].name == g.mission.robots[i].name);
      CHECK(g.world.robots[i].start.x_m == doctest::Approx(g.mission.robots[i].start.x_m));
    }
    const mission_gen::Coverage c = mission_gen::coverage(g);
    CHECK(c.robots >= 1);
    CHECK(c.robots <= 6);
    ++sizes[c.robots];
    CHECK(c.min_leg_m >= 1.0 - 1e-9);
    CHECK(c.max_leg_m <= 25.0 + 1e-9);
    CHECK(c.min_speed_mps >= 0.1 - 1e-9);
    CHECK(c.max_speed_mps <= mission_gen::kTopSpeedMps + 1e-9);
    CHECK(c.min_dropoff_m >= 0.3 - 1e-9);
    CHECK(c.max_dropoff_m <= 2.0 + 1e-9);
    CHECK(c.max_noise_gain <= 0.3 + 1e-9);
    CHECK(g.mission.criteria.tmax_s > 0);
    cov.push_back(c);
  }
  std::filesystem::remove_all(dir);
  // Every team size, small teams most often (as people write them).
  for (std::size_t n = 1; n <= 6; ++n) CHECK(sizes[n] >= 25);
  CHECK(sizes[2] > sizes[6]);

  // Each feature in a fair share of the 500 missions.
  const auto count = [&cov](auto pred) { return std::count_if(cov.begin(), cov.end(), pred); };
  using C = const mission_gen::Coverage&;
  CHECK(count([](C c) { return c.noise_redrawn_every_cycle > 0; }) >= 50);
  CHECK(count([](C c) { return c.noise_held_whole_leg > 0; }) >= 50);
  CHECK(count([](C c) { return c.spins > 0; }) >= 50);
  CHECK(count([](C c) { return c.spin_offsets > 0; }) >= 50);
  CHECK(count([](C c) { return c.loops > 0; }) >= 50);
  CHECK(count([](C c) { return c.notified_from_moving > 0; }) >= 50);
  CHECK(count([](C c) { return c.notified_from_spin > 0; }) >= 25);
  CHECK(count([](C c) { return c.notified_from_stop > 0; }) >= 50);
  CHECK(count([](C c) { return c.at_goal_racing_notified > 0; }) >= 50);
  CHECK(count([](C c) { return c.multi_recipient_messages > 0; }) >= 25);
  CHECK(count([](C c) { return c.crossing_paths > 0; }) >= 50);
  CHECK(count([](C c) { return c.world.pillars > 0; }) >= 50);
  CHECK(count([](C c) { return c.world.wall_stubs > 0; }) >= 50);
  CHECK(count([](C c) { return c.world.doorways > 0; }) >= 50);
  CHECK(count([](C c) { return c.world.alcoves > 0; }) >= 50);
  CHECK(count([](C c) { return c.systematic_error_robots > 0; }) >= 50);
  CHECK(count([](C c) { return c.lossy_radio; }) >= 50);
  CHECK(count([](C c) { return c.slow_radio; }) >= 50);
  CHECK(count([](C c) { return c.max_random_trans > 0.015; }) >= 50);   // large random errors ...
  CHECK(count([](C c) { return c.min_random_trans < 0.006; }) >= 50);   // ... and small ones
}

TEST_CASE("generator: the robot range is honoured and checked") {
  for (std::uint64_t s = 1; s <= 40; ++s) {
    const auto g = gen(s, 3, 4);
    CHECK(g.mission.robots.size() >= 3);
    CHECK(g.mission.robots.size() <= 4);
  }
  CHECK(gen(5, 1, 1).mission.robots.size() == 1);
  CHECK_THROWS_AS(gen(1, 0, 3), std::invalid_argument);
  CHECK_THROWS_AS(gen(1, 4, 3), std::invalid_argument);
  CHECK_THROWS_AS(gen(1, 1, 7), std::invalid_argument);
}

TEST_CASE("generator: the floor plan's script and data name every robot") {
  const auto g = gen(3);
  const std::string base = p3at::test::scratch_path("plan");
  CHECK(mission_gen::draw_picture(g, base, "") == "");  // no gnuplot: files only
  std::ifstream gp(base + ".gp");
  std::stringstream s;
  s << gp.rdbuf();
  for (const auto& r : g.mission.robots) CHECK(s.str().find("'" + r.name + "'") != std::string::npos);
  std::filesystem::remove(base + ".gp");
  std::filesystem::remove(base + ".dat");
}
