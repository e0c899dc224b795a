#include "p3at/validation/verify_output.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "p3at/common/number_format.hpp"

namespace p3at::vipars {
namespace {

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

std::string why_blocked(const std::string& why) {
  if (why == "stuck") return "stuck on its path (no quadrature direction reaches the state's trigger)";
  if (why == "waiting") return "waiting for a message nobody will send";
  if (why == "stuck-waiting") return "stuck on its path, then waiting for a message nobody will send";
  if (why == "loop") return "still looping after the event budget";
  return why;
}

}  // namespace

void locate_from_file(verifier::VerifyResult& result, const std::string& mission_file) {
  std::ifstream in(mission_file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  verifier::locate_in_mission_file(result, text, mission_file);
}

nlohmann::json approximations_json(const std::vector<verifier::Approximation>& approximations) {
  nlohmann::json out = nlohmann::json::array();
  for (const verifier::Approximation& a : approximations) {
    nlohmann::json e{{"kind", verifier::to_string(a.kind)}, {"robot", a.robot_name}, {"state", a.state},
                     {"where", a.where}, {"detail", a.detail}, {"vouched", a.vouched}};
    if (a.measured_error) {
      e["measured_error"] = {{"time", a.measured_error->time}, {"radius", a.measured_error->radius},
                             {"joint", a.measured_error->joint}};
    } else {
      e["measured_error"] = nullptr;
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::string approximations_text(const std::vector<verifier::Approximation>& approximations) {
  if (approximations.empty()) return "";
  std::string s = "  approximations of the model on this mission (docs/verifier.md):\n";
  for (const verifier::Approximation& a : approximations) {
    std::string measured = "never measured";
    if (a.measured_error) {
      measured = "measured error " + format_fixed(a.measured_error->time, 3) + " / " + format_fixed(a.measured_error->radius, 3) +
                 " / " + format_fixed(a.measured_error->joint, 3);
    }
    s += std::string("    ") + (a.vouched ? "vouched  " : "UNVOUCHED") + " " + verifier::to_string(a.kind) + " " +
         a.robot_name + (a.state.empty() ? "" : " '" + a.state + "'") + (a.where.empty() ? "" : " at " + a.where) +
         " (" + measured + ")\n      " + a.detail + "\n";
  }
  return s;
}

nlohmann::json verify_json(const mission::Mission& mission, const verifier::VerifyResult& r) {
  nlohmann::json j;
  j["mission"] = mission.name;
  j["decision"] = verifier::to_string(verifier::decision(r));
  j["evaluable"] = r.evaluable;
  j["p_joint_decided"] = r.p_joint_decided;
  j["decided_at"] = {{"tmax_s", r.decided_tmax_s},
                     {"rmax_m", r.decided_rmax_m},
                     {"widened", r.widened},
                     {"floor_time_s", r.floors.time_s},
                     {"floor_radius_m", r.floors.radius_m}};
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
                      {"final_sd_m", p.final_sd_m}, {"dist_mean_m", p.dist_mean_m}, {"dist_sd_m", p.dist_sd_m},
                      {"p_blocked", p.p_blocked},
                      {"finishes", p.finishes}});
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
  j["budget_merged_mass"] = r.budget_merged_mass;
  j["blocked_mass"] = r.blocked_mass;
  nlohmann::json blocked = nlohmann::json::array();
  for (const verifier::BlockedRobot& b : r.blocked) {
    blocked.push_back({{"robot", b.name}, {"state", b.state_name}, {"where", b.where}, {"why", b.why},
                       {"x_m", b.x_m}, {"y_m", b.y_m}, {"probability", b.probability}});
  }
  j["blocked"] = blocked;
  j["approximations"] = approximations_json(r.approximations);
  j["loop_cutoff_mass"] = r.loop_cutoff_mass;
  j["work_cutoff_mass"] = r.work_cutoff_mass;
  j["work_cycles"] = r.work_cycles;
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
  s += "mission " + mission.name + ": Tmax " + format_fixed(r.tmax_s, 1) + " s, Rmax " + format_fixed(r.rmax_m, 2) +
       " m, threshold " + format_fixed(r.threshold, 3) + "\n";
  s += "  P(t <= Tmax)                 " + format_fixed(r.p_time, 4) +
       (r.branches > 0 ? "   (completion " + format_fixed(r.completion_mean_s, 1) + " ± " + format_fixed(r.completion_sd_s, 1) + " s)"
                       : "   (no branch completes: the mission never finishes)") +
       "\n";
  s += "  P(every r_i <= Rmax)         " + format_fixed(r.p_radius, 4) + "\n";
  s += "  P(t <= Tmax and r_i <= Rmax) " + format_fixed(r.p_joint, 4) + "\n";
  s += "  decided at " + format_fixed(r.decided_tmax_s, 2) + " s, " + format_fixed(r.decided_rmax_m, 3) + " m (" +
       verifier::decision_margin_text(r) + "): P " + format_fixed(r.p_joint_decided, 4) + "\n";
  for (std::size_t i = 0; i < r.robots.size(); ++i) {
    const verifier::RobotPrediction& p = r.robots[i];
    if (!p.finishes) {
      // No branch has it finish: there is no finishing time or place to print.
      s += "  " + p.name + ": BLOCKED, never reaches a final state";
      for (const verifier::BlockedRobot& b : r.blocked) {
        if (b.robot != i) continue;
        s += "; P " + format_fixed(b.probability, 3) + " " + why_blocked(b.why) + " in state '" + b.state_name + "'" +
             (b.where.empty() ? "" : " (" + b.where + ")") + " near (" + format_fixed(b.x_m, 2) + ", " + format_fixed(b.y_m, 2) + ")";
      }
      s += "\n";
      continue;
    }
    s += "  " + p.name + ": done at " + format_fixed(p.finish_mean_s, 1) + " ± " + format_fixed(p.finish_sd_s, 1) +
         " s, ends near (" + format_fixed(p.final_x_m, 2) + ", " + format_fixed(p.final_y_m, 2) + ") ± " +
         format_fixed(p.final_sd_m, 2) + " m, " + format_fixed(p.dist_mean_m, 2) + " m from its goal, P(r <= Rmax) " +
         format_fixed(p.p_radius, 4) + "\n";
  }
  for (const verifier::CriterionVerdict& c : r.criteria) {
    s += "  criterion " + c.name + ": P = " + format_fixed(c.probability, 4) + ", required " +
         format_fixed(c.required, 3) + (c.holds ? " (holds)" : " (FAILS)") + "\n";
  }
  if (r.pruned_mass > 0.0 || r.blocked_mass > 0.0) {
    s += "  probability mass pruned " + format_scientific(r.pruned_mass, 2) + ", blocked (never finishes) " +
         format_scientific(r.blocked_mass, 2) + "\n";
  }
  if (r.budget_merged_mass > 0.0) {
    s += "  probability mass merged over the branch budget " + format_scientific(r.budget_merged_mass, 2) +
         " (budget.max_branches; places merged coarsely)\n";
  }
  for (const verifier::BlockedRobot& b : r.blocked) {
    if (b.robot < r.robots.size() && !r.robots[b.robot].finishes) continue;  // said above
    s += "  blocked with P " + format_scientific(b.probability, 2) + ": " + b.name + " " + why_blocked(b.why) + " in state '" +
         b.state_name + "'" + (b.where.empty() ? "" : " (" + b.where + ")") + " near (" + format_fixed(b.x_m, 2) + ", " +
         format_fixed(b.y_m, 2) + ")\n";
  }
  s += approximations_text(r.approximations);
  if (r.loop_cutoff_mass > 0.0) {
    s += "  probability mass of loop laps beyond the budget " + format_scientific(r.loop_cutoff_mass, 2) +
         " (counted as failure)\n";
  }
  if (r.work_cutoff_mass > 0.0) {
    s += "  the verifier's work budget (" + std::to_string(r.work_cycles) +
         " robot cycles simulated, budget.max_work_cycles) ran out with probability mass " +
         format_scientific(r.work_cutoff_mass, 2) + " unevaluated (counted as failure)\n";
  }
  s += "  " + std::to_string(r.subsystems) + " subsystems evaluated, " + std::to_string(r.branches) +
       " ordering branch(es)\n";
  if (r.grid) {
    const verifier::Grid& g = *r.grid;
    s += "\n  P(t <= Tmax and r_i <= Rmax): rows Tmax (s), columns Rmax (m)\n  Tmax\\Rmax";
    const auto cols = shown(g.rmax.size(), kMaxTableColumns);
    const auto rows = shown(g.tmax.size(), kMaxTableRows);
    for (const std::size_t c : cols) s += format_fixed(g.rmax[c], 2, 7);
    s += "\n";
    for (const std::size_t row : rows) {
      s += "  " + format_fixed(g.tmax[row], 1, 9);
      for (const std::size_t c : cols) s += format_fixed(g.p_joint[row][c], 3, 7);
      s += "\n";
    }
  }
  switch (verifier::decision(r)) {
    case verifier::Decision::go: s += "decision: GO\n"; break;
    case verifier::Decision::no_go: s += "decision: NO-GO\n"; break;
    case verifier::Decision::cannot_evaluate:
      s += "decision: CANNOT EVALUATE: the probabilities say GO, but the model does not vouch for this mission (" +
           verifier::unvouched_kinds(r.approximations) + "); the gate refuses it unless the operator accepts\n";
      break;
  }
  for (const std::string& f : r.failed) s += "  failed: " + f + "\n";
  return s;
}

}  // namespace p3at::vipars
