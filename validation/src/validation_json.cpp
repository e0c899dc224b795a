#include "p3at/validation/validation_json.hpp"

#include <utility>
#include <vector>

namespace p3at::vipars {
namespace {

using Json = nlohmann::ordered_json;

void put_estimate(Json& j, const std::string& key, const team_sim::Estimate& e) {
  j[key] = e.p;
  j[key + "_ci_low"] = e.ci_low;
  j[key + "_ci_high"] = e.ci_high;
}

Json estimates(const std::vector<team_sim::Estimate>& row, double team_sim::Estimate::*member) {
  Json out = Json::array();
  for (const auto& e : row) out.push_back(e.*member);
  return out;
}

Json table(const team_sim::EmpiricalGrid& g, double team_sim::Estimate::*member) {
  Json out = Json::array();
  for (const auto& row : g.joint) out.push_back(estimates(row, member));
  return out;
}

Json grid_json(const team_sim::EmpiricalGrid& g, double region_low, double region_high) {
  Json regions = Json::array();
  for (const auto& row : g.joint) {
    Json r = Json::array();
    for (const auto& e : row) r.push_back(team_sim::to_string(team_sim::classify(e.p, region_low, region_high)));
    regions.push_back(std::move(r));
  }
  Json j;
  j["tmax"] = g.tmax;
  j["rmax"] = g.rmax;
  j["p_time"] = estimates(g.time, &team_sim::Estimate::p);
  j["p_radius"] = estimates(g.radius, &team_sim::Estimate::p);
  j["p_joint"] = table(g, &team_sim::Estimate::p);
  j["region"] = std::move(regions);
  j["p_time_ci_low"] = estimates(g.time, &team_sim::Estimate::ci_low);
  j["p_time_ci_high"] = estimates(g.time, &team_sim::Estimate::ci_high);
  j["p_radius_ci_low"] = estimates(g.radius, &team_sim::Estimate::ci_low);
  j["p_radius_ci_high"] = estimates(g.radius, &team_sim::Estimate::ci_high);
  j["p_joint_ci_low"] = table(g, &team_sim::Estimate::ci_low);
  j["p_joint_ci_high"] = table(g, &team_sim::Estimate::ci_high);
  return j;
}

}  // namespace

nlohmann::ordered_json validation_json(const ValidationSummary& s) {
  const team_sim::EmpiricalPoint& p = *s.point;
  Json j;
  j["mission"] = s.mission_name;
  j["tmax_s"] = p.tmax_s;
  j["rmax_m"] = p.rmax_m;
  j["threshold"] = s.threshold;
  put_estimate(j, "p_time", p.time);
  put_estimate(j, "p_radius", p.radius);
  put_estimate(j, "p_joint", p.joint);
  j["runs"] = p.runs;
  j["failed_runs"] = p.failed_runs;
  j["robots"] = Json::array();
  for (const auto& robot : p.robots) {
    Json jr;
    jr["name"] = robot.name;
    put_estimate(jr, "p_radius", robot.radius);
    jr["dist_mean_m"] = robot.dist_mean_m;
    jr["dist_sd_m"] = robot.dist_sd_m;
    j["robots"].push_back(std::move(jr));
  }
  j["completion_mean_s"] = p.completion_mean_s ? Json(*p.completion_mean_s) : Json(nullptr);
  j["completion_sd_s"] = p.completion_sd_s ? Json(*p.completion_sd_s) : Json(nullptr);
  if (s.grid) j["grid"] = grid_json(*s.grid, s.region_low, s.region_high);
  j["seed"] = s.seed;
  j["world"] = s.world_file;
  j["mission_file"] = s.mission_file;
  return j;
}

}  // namespace p3at::vipars
