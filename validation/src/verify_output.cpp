#include "p3at/validation/verify_output.hpp"

#include <algorithm>
#include <cstdio>

namespace p3at::vipars {
namespace {

/// `v` with `decimals` digits after the point, right-aligned in `width` columns.
std::string fixed(double v, int decimals, int width = 0) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%*.*f", width, decimals, v);
  return buf;
}

std::string scientific(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  return buf;
}

// At most this many rows/columns in the text table; larger grids are shown
// every k-th value (the JSON always has all of them).
constexpr std::size_t kMaxTableRows = 16;
constexpr std::size_t kMaxTableColumns = 11;

std::vector<std::size_t> shown(std::size_t n, std::size_t max) {
  std::vector<std::size_t> idx;
  const std::size_t step = (n + max - 1) / max;
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, step)) idx.push_back(i);
  if (!idx.empty() && idx.back() != n - 1) idx.push_back(n - 1);
  return idx;
}

}  // namespace

nlohmann::json verify_json(const mission::Mission& mission, const verifier::VerifyResult& r) {
  nlohmann::json j;
  j["mission"] = mission.name;
  j["decision"] = r.go ? "go" : "no-go";
  j["tmax_s"] = r.tmax_s;
  j["rmax_m"] = r.rmax_m;
  j["threshold"] = r.threshold;
  j["p_time"] = r.p_time;
  j["p_radius"] = r.p_radius;
  j["p_joint"] = r.p_joint;
  j["completion_mean_s"] = r.completion_mean_s;
  j["completion_sd_s"] = r.completion_sd_s;
  nlohmann::json robots = nlohmann::json::array();
  for (const verifier::RobotPrediction& p : r.robots) {
    robots.push_back({{"name", p.name}, {"p_radius", p.p_radius}, {"finish_mean_s", p.finish_mean_s},
                      {"finish_sd_s", p.finish_sd_s}, {"final_x_m", p.final_x_m}, {"final_y_m", p.final_y_m},
                      {"final_sd_m", p.final_sd_m}, {"dist_mean_m", p.dist_mean_m}});
  }
  j["robots"] = robots;
  nlohmann::json criteria = nlohmann::json::array();
  for (const verifier::CriterionVerdict& c : r.criteria) {
    criteria.push_back({{"name", c.name}, {"probability", c.probability}, {"required", c.required},
                        {"holds", c.holds}, {"explanation", c.explanation}});
  }
  j["criteria"] = criteria;
  j["failed"] = r.failed;
  j["pruned_mass"] = r.pruned_mass;
  j["blocked_mass"] = r.blocked_mass;
  j["loop_cutoff_mass"] = r.loop_cutoff_mass;
  j["branches"] = r.branches;
  j["subsystems"] = r.subsystems;
  if (r.grid) {
    nlohmann::json g;
    g["tmax"] = r.grid->tmax;
    g["rmax"] = r.grid->rmax;
    g["p_time"] = r.grid->p_time;
    g["p_radius"] = r.grid->p_radius;
    g["p_joint"] = r.grid->p_joint;
    nlohmann::json regions = nlohmann::json::array();
    for (const auto& row : r.grid->region) {
      nlohmann::json out = nlohmann::json::array();
      for (const verifier::Region region : row) out.push_back(verifier::to_string(region));
      regions.push_back(out);
    }
    g["region"] = regions;
    j["grid"] = g;
  }
  return j;
}

std::string verify_text(const mission::Mission& mission, const verifier::VerifyResult& r) {
  std::string s;
  s += "mission " + mission.name + ": Tmax " + fixed(r.tmax_s, 1) + " s, Rmax " + fixed(r.rmax_m, 2) +
       " m, threshold " + fixed(r.threshold, 3) + "\n";
  s += "  P(t <= Tmax)                 " + fixed(r.p_time, 4) + "   (completion " +
       fixed(r.completion_mean_s, 1) + " ± " + fixed(r.completion_sd_s, 1) + " s)\n";
  s += "  P(every r_i <= Rmax)         " + fixed(r.p_radius, 4) + "\n";
  s += "  P(t <= Tmax and r_i <= Rmax) " + fixed(r.p_joint, 4) + "\n";
  for (const verifier::RobotPrediction& p : r.robots) {
    s += "  " + p.name + ": done at " + fixed(p.finish_mean_s, 1) + " ± " + fixed(p.finish_sd_s, 1) +
         " s, ends near (" + fixed(p.final_x_m, 2) + ", " + fixed(p.final_y_m, 2) + ") ± " +
         fixed(p.final_sd_m, 2) + " m, " + fixed(p.dist_mean_m, 2) + " m from its goal, P(r <= Rmax) " +
         fixed(p.p_radius, 4) + "\n";
  }
  for (const verifier::CriterionVerdict& c : r.criteria) {
    s += "  criterion " + c.name + ": P = " + fixed(c.probability, 4) + ", required " +
         fixed(c.required, 3) + (c.holds ? " (holds)" : " (FAILS)") + "\n";
  }
  if (r.pruned_mass > 0.0 || r.blocked_mass > 0.0) {
    s += "  probability mass pruned " + scientific(r.pruned_mass) + ", blocked (never finishes) " +
         scientific(r.blocked_mass) + "\n";
  }
  if (r.loop_cutoff_mass > 0.0) {
    s += "  probability mass of loop laps beyond the budget " + scientific(r.loop_cutoff_mass) +
         " (counted as failure)\n";
  }
  s += "  " + std::to_string(r.subsystems) + " subsystems evaluated, " + std::to_string(r.branches) +
       " ordering branch(es)\n";
  if (r.grid) {
    const verifier::Grid& g = *r.grid;
    s += "\n  P(t <= Tmax and r_i <= Rmax): rows Tmax (s), columns Rmax (m)\n  Tmax\\Rmax";
    const auto cols = shown(g.rmax.size(), kMaxTableColumns);
    const auto rows = shown(g.tmax.size(), kMaxTableRows);
    for (const std::size_t c : cols) s += fixed(g.rmax[c], 2, 7);
    s += "\n";
    for (const std::size_t row : rows) {
      s += "  " + fixed(g.tmax[row], 1, 9);
      for (const std::size_t c : cols) s += fixed(g.p_joint[row][c], 3, 7);
      s += "\n";
    }
  }
  s += std::string(r.go ? "decision: GO" : "decision: NO-GO") + "\n";
  for (const std::string& f : r.failed) s += "  failed: " + f + "\n";
  return s;
}

}  // namespace p3at::vipars
