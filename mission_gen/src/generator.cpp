// generate(): routes, messages, world, criteria, then the two files, each
// loaded back by its own loader (the loaders, not the generator, say what is valid).

#include <cmath>
#include <stdexcept>

#include "gen_internal.hpp"
#include "p3at/mission/loader.hpp"

namespace p3at::mission_gen {
namespace {

std::string describe(const TeamPlan& team, int layout, const WorldPlan& world) {
  static const char* const kLayouts[] = {"an open room", "a hallway", "two rooms"};
  std::string s = std::to_string(team.robots.size()) + (team.robots.size() == 1 ? " robot in " : " robots in ") + kLayouts[layout];
  if (world.features.doorways > 0) s += " with doorways";
  std::size_t waits = 0, recalls = 0, patrols = 0, spins = 0;
  for (const RobotPlan& r : team.robots) {
    for (const Op& op : r.ops) {
      waits += op.kind == Op::Kind::wait;
      patrols += op.kind == Op::Kind::patrol;
      spins += op.kind == Op::Kind::spin;
      recalls += !op.recall.empty();
    }
  }
  if (spins) s += "; " + std::to_string(spins) + " spins";
  if (waits) s += "; " + std::to_string(waits) + " waits for a teammate";
  if (recalls) s += "; " + std::to_string(recalls) + " recalls mid-way";
  if (patrols) s += "; " + std::to_string(patrols) + " patrols until relieved";
  return s;
}

}  // namespace

GeneratedMission generate(const GenerateOptions& options) {
  if (options.min_robots < 1 || options.max_robots > 6 || options.min_robots > options.max_robots) {
    throw std::invalid_argument("robots must be A:B with 1 <= A <= B <= 6");
  }
  GenRng rng(options.seed);
  // Weighted toward small teams, as people write them.
  static const double kTeamWeights[] = {0.22, 0.3, 0.2, 0.12, 0.08, 0.08};
  double total = 0;
  for (std::size_t n = options.min_robots; n <= options.max_robots; ++n) total += kTeamWeights[n - 1];
  double x = rng.unit() * total;
  std::size_t robots = options.max_robots;
  for (std::size_t n = options.min_robots; n <= options.max_robots; ++n) {
    if (x < kTeamWeights[n - 1]) {
      robots = n;
      break;
    }
    x -= kTeamWeights[n - 1];
  }
  // A hallway for teams of up to three (one lane each); rooms for any team.
  const int layout = robots <= 3 ? static_cast<int>(rng.weighted({0.4, 0.3, 0.3}))
                                 : (rng.chance(0.55) ? 0 : 2);

  TeamPlan team = draw_routes(rng, robots, layout == 1);
  draw_messages(rng, team);
  WorldPlan world = draw_world(rng, team, layout);
  shift_to_origin(team, world);

  GeneratedMission g;
  g.seed = options.seed;
  g.name = "gen_" + std::to_string(options.seed);
  mission::Criteria c;
  const double nominal = nominal_time_s(team);
  c.tmax_s = std::ceil((nominal * rng.uniform(1.05, 1.5) + 10.0) / 5.0) * 5.0;
  c.rmax_m = round_to(rng.uniform(0.3, 2.0), 0.1);
  static const std::vector<double> kThresholds{0.8, 0.8, 0.8, 0.8, 0.9, 0.7, 0.95};
  c.threshold = rng.pick(kThresholds);
  const std::string description = describe(team, layout, world);
  g.mission_yaml = mission_text(team, c, g.name, description, options.seed);
  g.world_yaml = world_text(team, world, options.seed);
  g.features = world.features;
  for (const RobotPlan& r : team.robots) {
    RoutePlan route{r.name, {r.start}};
    for (const Op& op : r.ops) {
      if (op.kind == Op::Kind::go) route.points.push_back(op.goal);
      if (op.kind == Op::Kind::patrol) {
        route.points.push_back(op.goal);
        route.points.push_back(op.goal2);
        route.points.push_back(op.goal);
      }
    }
    g.routes.push_back(route);
  }
  try {
    g.mission = mission::parse_mission(g.mission_yaml, g.name + "/mission.yaml");
    g.world = sim::parse_world(g.world_yaml, g.name + "/world.yaml");
  } catch (const std::exception& e) {
    throw std::logic_error("generated mission for seed " + std::to_string(options.seed) + " does not load: " + e.what());
  }
  return g;
}

}  // namespace p3at::mission_gen
