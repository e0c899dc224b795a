// The CI gate's baseline file (baseline.hpp).

#include "p3at/crosscheck/baseline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "p3at/common/number_format.hpp"

namespace p3at::crosscheck {

std::vector<BaselineEntry> baseline_from(const std::vector<MissionResult>& results, const Bounds& b, double margin) {
  std::vector<BaselineEntry> out;
  for (const MissionResult& r : results) {
    if (!r.error.empty()) continue;
    BaselineEntry e;
    e.name = r.name;
    const auto lim = [margin](double measured) { return std::min(1.0, std::ceil((measured + margin) * 1000) / 1000); };
    if (r.generator_seed) {
      e.time = lim(r.score.time.strict);
      e.radius = lim(r.score.radius.strict);
      e.joint = lim(r.score.joint.strict);
      e.time_tolerant = lim(r.score.time.tolerant);
      e.radius_tolerant = lim(r.score.radius.tolerant);
      e.joint_tolerant = lim(r.score.joint.tolerant);
      e.overconfident_go_cells = r.score.overconfident_go_cells + r.score.overconfident_go_cells / 10 + 1;
    } else {
      // Shipped missions: within the bounds with the 1 % shift, never an
      // over-confident GO, and strictly no worse than the bound or than
      // measured (1,000 runs' own noise reaches a few hundredths strictly).
      e.time_tolerant = b.time;
      e.radius_tolerant = b.radius;
      e.joint_tolerant = b.joint;
      e.time = std::max(b.time, lim(r.score.time.strict));
      e.radius = std::max(b.radius, lim(r.score.radius.strict));
      e.joint = std::max(b.joint, lim(r.score.joint.strict));
      e.overconfident_go_cells = 0;
    }
    out.push_back(e);
  }
  return out;
}

nlohmann::ordered_json baseline_json(const std::vector<BaselineEntry>& entries, const std::string& how_made) {
  nlohmann::ordered_json j;
  j["made_by"] = how_made;
  j["missions"] = nlohmann::ordered_json::array();
  for (const BaselineEntry& e : entries) {
    j["missions"].push_back({{"name", e.name},
                             {"time", e.time},
                             {"radius", e.radius},
                             {"joint", e.joint},
                             {"time_tolerant", e.time_tolerant},
                             {"radius_tolerant", e.radius_tolerant},
                             {"joint_tolerant", e.joint_tolerant},
                             {"overconfident_go_cells", e.overconfident_go_cells}});
  }
  return j;
}

std::vector<BaselineEntry> load_baseline(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read baseline " + path);
  std::stringstream s;
  s << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(s.str());
    std::vector<BaselineEntry> out;
    for (const nlohmann::json& m : j.at("missions")) {
      BaselineEntry e;
      e.name = m.at("name").get<std::string>();
      e.time = m.at("time").get<double>();
      e.radius = m.at("radius").get<double>();
      e.joint = m.at("joint").get<double>();
      e.time_tolerant = m.at("time_tolerant").get<double>();
      e.radius_tolerant = m.at("radius_tolerant").get<double>();
      e.joint_tolerant = m.at("joint_tolerant").get<double>();
      e.overconfident_go_cells = m.at("overconfident_go_cells").get<std::size_t>();
      out.push_back(e);
    }
    return out;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": not a baseline file (" + std::string(e.what()) + ")");
  }
}

std::vector<std::string> check_baseline(const std::vector<MissionResult>& results, const std::vector<BaselineEntry>& baseline) {
  std::vector<std::string> out;
  for (const MissionResult& r : results) {
    const auto it = std::find_if(baseline.begin(), baseline.end(), [&r](const BaselineEntry& e) { return e.name == r.name; });
    if (it == baseline.end()) {
      out.push_back(r.name + ": not in the baseline (record one with --write-baseline)");
      continue;
    }
    if (!r.error.empty()) {
      out.push_back(r.name + ": could not run: " + r.error);
      continue;
    }
    const auto over = [&](const char* what, double measured, double limit) {
      if (measured > limit) {
        out.push_back(r.name + ": " + what + " " + format_fixed(measured, 3) + " > " + format_fixed(limit, 3));
      }
    };
    over("time strict", r.score.time.strict, it->time);
    over("radius strict", r.score.radius.strict, it->radius);
    over("joint strict", r.score.joint.strict, it->joint);
    over("time 1 % shift", r.score.time.tolerant, it->time_tolerant);
    over("radius 1 % shift", r.score.radius.tolerant, it->radius_tolerant);
    over("joint 1 % shift", r.score.joint.tolerant, it->joint_tolerant);
    if (r.evaluable && r.score.overconfident_go_cells > it->overconfident_go_cells) {
      out.push_back(r.name + ": " + std::to_string(r.score.overconfident_go_cells) + " over-confident GO cells > " +
                    std::to_string(it->overconfident_go_cells));
    }
    // A safety criterion the gate would pass where the runs refute it: none
    // allowed on a mission the verifier vouches for.
    if (r.evaluable && r.separation && r.separation->overconfident_points > 0) {
      out.push_back(r.name + ": " + std::to_string(r.separation->overconfident_points) +
                    " over-confident separation points > 0");
    }
  }
  return out;
}

}  // namespace p3at::crosscheck
