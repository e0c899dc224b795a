// vipars generate --seed S | --seeds A:B [--robots A:B] [--out DIR] [--picture] [--coverage]
// Generated missions for the cross-check campaign (docs/crosscheck.md): a
// mission, its world and its criteria, the same bytes for the same seed.

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "p3at/mission_gen/generator.hpp"

namespace p3at::vipars {
namespace {

struct GenerateFlags {
  std::optional<std::uint64_t> seed;
  std::string seeds;
  std::string robots = "1:6";
  std::string out;
  bool picture = false;
  bool coverage = false;
};

// "A:B" with A <= B, both whole.
bool parse_pair(const std::string& text, std::uint64_t& a, std::uint64_t& b) {
  unsigned long long x = 0, y = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%llu:%llu%c", &x, &y, &tail) != 2 || x > y) return false;
  a = x;
  b = y;
  return true;
}

int run_generate(const GenerateFlags& f) {
  std::uint64_t first = 0, last = 0, lo = 0, hi = 0;
  if (f.seed && !f.seeds.empty()) {
    std::fprintf(stderr, "vipars generate: give --seed S or --seeds A:B, not both\n");
    return kExitBadInput;
  }
  if (f.seed) {
    first = last = *f.seed;
  } else if (!parse_pair(f.seeds, first, last)) {
    std::fprintf(stderr, "vipars generate: --seeds: expected A:B with A <= B, got '%s'\n", f.seeds.c_str());
    return kExitBadInput;
  }
  if (!parse_pair(f.robots, lo, hi) || lo < 1 || hi > 6) {
    std::fprintf(stderr, "vipars generate: --robots: expected A:B with 1 <= A <= B <= 6, got '%s'\n", f.robots.c_str());
    return kExitBadInput;
  }
  const bool one = first == last && f.seed;
  std::vector<mission_gen::Coverage> covered;
  for (std::uint64_t s = first; s <= last; ++s) {
    mission_gen::GenerateOptions o;
    o.seed = s;
    o.min_robots = lo;
    o.max_robots = hi;
    try {
      const mission_gen::GeneratedMission g = mission_gen::generate(o);
      if (f.coverage) covered.push_back(mission_gen::coverage(g));
      if (!f.out.empty()) {
        const std::string dir = one ? f.out : f.out + "/" + g.name;
        mission_gen::write_generated(g, dir);
        if (f.picture) {
          const std::string err = mission_gen::draw_picture(g, dir + "/plan");
          if (!err.empty()) std::fprintf(stderr, "vipars generate: picture of %s: %s\n", g.name.c_str(), err.c_str());
        }
        std::printf("%s\n", dir.c_str());
      } else if (!f.coverage) {
        std::fputs(g.mission_yaml.c_str(), stdout);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vipars generate: %s\n", e.what());
      return kExitFailed;
    }
  }
  if (f.coverage) std::fputs(mission_gen::coverage_table(covered).c_str(), stdout);
  return kExitOk;
}

}  // namespace

void register_generate(CLI::App& app, int& exit_status) {
  auto f = std::make_shared<GenerateFlags>();
  CLI::App* sub = app.add_subcommand(
      "generate", "Write a generated mission, its world and its criteria, deterministically from a seed (docs/crosscheck.md)");
  sub->add_option("--seed", f->seed, "The mission's seed");
  sub->add_option("--seeds", f->seeds, "A range of seeds A:B (with --out: one folder gen_S per seed)");
  sub->add_option("--robots", f->robots, "Team sizes to draw from, A:B within 1:6 (default 1:6)");
  sub->add_option("--out", f->out,
                  "Folder for mission.yaml and world.yaml (with --seeds: its gen_S subfolders); without it the "
                  "mission is printed");
  sub->add_flag("--picture", f->picture, "With --out: also a floor plan, plan.png (gnuplot)");
  sub->add_flag("--coverage", f->coverage, "Print how many missions exercise each feature of the format");
  sub->callback([f, &exit_status] { exit_status = run_generate(*f); });
}

}  // namespace p3at::vipars
