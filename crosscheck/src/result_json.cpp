// The campaign's lines, summary and JSON (result_json.hpp).

#include "p3at/crosscheck/result_json.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "p3at/common/number_format.hpp"
#include "p3at/common/text_columns.hpp"

namespace p3at::crosscheck {
namespace {

using Json = nlohmann::ordered_json;

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json error_json(const ErrorSummary& e) {
  Json j;
  j["strict"] = e.strict;
  j["tolerant"] = e.tolerant;
  j["strict_at"] = {{"tmax_s", number_or_null(e.strict_at_tmax_s)}, {"rmax_m", number_or_null(e.strict_at_rmax_m)},
                    {"verify", e.strict_verify}, {"validate", e.strict_validate}};
  j["tolerant_at"] = {{"tmax_s", number_or_null(e.tolerant_at_tmax_s)}, {"rmax_m", number_or_null(e.tolerant_at_rmax_m)},
                      {"verify", e.tolerant_verify}, {"validate", e.tolerant_validate}};
  j["points"] = e.points;
  return j;
}

/// The p-th percentile of `v` by nearest rank (v sorted, not empty).
double nearest_rank(const std::vector<double>& v, double p) {
  const std::size_t k = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(k, 1, v.size()) - 1];
}

MetricStats stats(std::vector<double> v, double bound) {
  MetricStats s;
  s.missions = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.worst = v.back();
  s.p50 = nearest_rank(v, 50);
  s.p90 = nearest_rank(v, 90);
  s.p95 = nearest_rank(v, 95);
  s.within = static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [bound](double x) { return x <= bound; }));
  return s;
}

CampaignSummary::RobotDistances robot_distance_stats(const std::vector<MissionResult>& results) {
  CampaignSummary::RobotDistances s;
  std::vector<double> ratios, mean_errors;
  for (const MissionResult& r : results) {
    if (!r.error.empty()) continue;
    for (const RobotDistance& d : r.robot_distances) {
      if (!d.comparable) continue;
      ratios.push_back(d.verify_sd_m / d.validate_sd_m);
      mean_errors.push_back(std::abs(d.verify_mean_m - d.validate_mean_m));
    }
  }
  s.robots = ratios.size();
  if (ratios.empty()) return s;
  std::sort(ratios.begin(), ratios.end());
  std::sort(mean_errors.begin(), mean_errors.end());
  s.sd_ratio_p10 = nearest_rank(ratios, 10);
  s.sd_ratio_p50 = nearest_rank(ratios, 50);
  s.sd_ratio_p90 = nearest_rank(ratios, 90);
  s.narrower = static_cast<std::size_t>(std::count_if(ratios.begin(), ratios.end(), [](double x) { return x < 2.0 / 3.0; }));
  s.wider = static_cast<std::size_t>(std::count_if(ratios.begin(), ratios.end(), [](double x) { return x > 1.5; }));
  s.mean_error_p50_m = nearest_rank(mean_errors, 50);
  s.mean_error_p90_m = nearest_rank(mean_errors, 90);
  s.mean_error_worst_m = mean_errors.back();
  return s;
}

Json stats_json(const MetricStats& s) {
  return Json{{"worst", s.worst}, {"p50", s.p50}, {"p90", s.p90}, {"p95", s.p95}, {"within", s.within},
              {"missions", s.missions}};
}

}  // namespace

CampaignSummary summarize(const std::vector<MissionResult>& results, const Bounds& b) {
  CampaignSummary s;
  s.missions = results.size();
  std::vector<double> ts, tt, rs, rt, js, jt, ss, st;
  for (const MissionResult& r : results) {
    s.runs += r.runs;
    if (!r.error.empty()) {
      ++s.could_not_run;
      continue;
    }
    ++s.scored;
    ts.push_back(r.score.time.strict);
    tt.push_back(r.score.time.tolerant);
    rs.push_back(r.score.radius.strict);
    rt.push_back(r.score.radius.tolerant);
    js.push_back(r.score.joint.strict);
    jt.push_back(r.score.joint.tolerant);
    if (r.separation) {
      ss.push_back(r.separation->error.strict);
      st.push_back(r.separation->error.tolerant);
      s.separation_overconfident_points += r.separation->overconfident_points;
      s.separation_overconfident_missions += r.separation->overconfident_points > 0;
    }
    s.all_within_strict += r.score.within(b, false);
    s.all_within_tolerant += r.score.within(b, true);
    if (!r.evaluable) {
      ++s.not_evaluable;
      s.overconfident_cells_not_evaluable += r.score.overconfident_go_cells;
    } else {
      s.overconfident_cells += r.score.overconfident_go_cells;
      s.overconfident_missions += r.score.overconfident_go_cells > 0;
    }
  }
  s.time_strict = stats(ts, b.time);
  s.time_tolerant = stats(tt, b.time);
  s.radius_strict = stats(rs, b.radius);
  s.radius_tolerant = stats(rt, b.radius);
  s.joint_strict = stats(js, b.joint);
  s.joint_tolerant = stats(jt, b.joint);
  s.separation_strict = stats(ss, b.radius);
  s.separation_tolerant = stats(st, b.radius);
  s.robot_distances = robot_distance_stats(results);
  return s;
}

Json mission_result_json(const MissionResult& r) {
  Json j;
  j["name"] = r.name;
  j["source"] = r.source;
  j["generator_seed"] = r.generator_seed ? Json(*r.generator_seed) : Json(nullptr);
  j["robots"] = r.robots;
  j["error"] = r.error.empty() ? Json(nullptr) : Json(r.error);
  j["evaluable"] = r.evaluable;
  j["approximations"] = r.approximations;
  j["calibration"] = r.calibration_note;
  j["runs"] = r.runs;
  j["failed_runs"] = r.failed_runs;
  j["tmax_range"] = r.tmax_range;
  j["rmax_range"] = r.rmax_range;
  j["criteria"] = {{"tmax_s", r.criteria_tmax_s}, {"rmax_m", r.criteria_rmax_m},
                   {"verify_p_joint", r.verify_p_joint}, {"validate_p_joint", r.validate_p_joint},
                   {"verify_go", r.verify_go}};
  j["time"] = error_json(r.score.time);
  j["radius"] = error_json(r.score.radius);
  j["joint"] = error_json(r.score.joint);
  j["overconfident_go_cells"] = r.score.overconfident_go_cells;
  Json cells = Json::array();
  for (const OverconfidentCell& c : r.score.overconfident) {
    cells.push_back({{"tmax_s", c.tmax_s}, {"rmax_m", c.rmax_m}, {"verify", c.verify}, {"validate", c.validate},
                     {"ci_low", c.ci_low}, {"ci_high", c.ci_high}});
  }
  j["overconfident_worst"] = cells;
  if (r.separation) {
    Json sep = error_json(r.separation->error);
    sep["d_range"] = r.separation->range;
    sep["overconfident_points"] = r.separation->overconfident_points;
    j["separation"] = sep;
  } else {
    j["separation"] = nullptr;
  }
  Json robots = Json::array();
  for (const RobotDistance& d : r.robot_distances) {
    robots.push_back({{"name", d.name}, {"verify_mean_m", d.verify_mean_m}, {"verify_sd_m", d.verify_sd_m},
                      {"validate_mean_m", d.validate_mean_m}, {"validate_sd_m", d.validate_sd_m},
                      {"comparable", d.comparable}});
  }
  j["robot_distances"] = robots;
  j["within_bounds_strict"] = r.error.empty() && r.score.within(Bounds{}, false);
  j["within_bounds_tolerant"] = r.error.empty() && r.score.within(Bounds{}, true);
  j["seconds"] = {{"calibrate", r.calibrate_s}, {"validate", r.validate_s}, {"verify", r.verify_s}, {"score", r.score_s}};
  j["folder"] = r.folder;
  j["reproduce"] = r.reproduce;
  return j;
}

namespace {

// A number, or NaN where the writer had one (nlohmann writes a NaN as null).
double number(const nlohmann::json& j) { return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>(); }

ErrorSummary error_from_json(const nlohmann::json& j) {
  ErrorSummary e;
  e.strict = number(j.at("strict"));
  e.tolerant = number(j.at("tolerant"));
  e.strict_at_tmax_s = number(j.at("strict_at").at("tmax_s"));
  e.strict_at_rmax_m = number(j.at("strict_at").at("rmax_m"));
  e.strict_verify = number(j.at("strict_at").at("verify"));
  e.strict_validate = number(j.at("strict_at").at("validate"));
  e.tolerant_at_tmax_s = number(j.at("tolerant_at").at("tmax_s"));
  e.tolerant_at_rmax_m = number(j.at("tolerant_at").at("rmax_m"));
  e.tolerant_verify = number(j.at("tolerant_at").at("verify"));
  e.tolerant_validate = number(j.at("tolerant_at").at("validate"));
  e.points = j.at("points").get<std::size_t>();
  return e;
}

}  // namespace

MissionResult mission_result_from_json(const nlohmann::json& j) {
  MissionResult r;
  r.name = j.at("name").get<std::string>();
  r.source = j.at("source").get<std::string>();
  if (!j.at("generator_seed").is_null()) r.generator_seed = j.at("generator_seed").get<std::uint64_t>();
  r.robots = j.at("robots").get<std::size_t>();
  if (!j.at("error").is_null()) r.error = j.at("error").get<std::string>();
  r.evaluable = j.at("evaluable").get<bool>();
  r.approximations = j.at("approximations").get<std::vector<std::string>>();
  r.calibration_note = j.at("calibration").get<std::string>();
  r.runs = j.at("runs").get<std::uint64_t>();
  r.failed_runs = j.at("failed_runs").get<std::uint64_t>();
  r.tmax_range = j.at("tmax_range").get<std::string>();
  r.rmax_range = j.at("rmax_range").get<std::string>();
  r.criteria_tmax_s = number(j.at("criteria").at("tmax_s"));
  r.criteria_rmax_m = number(j.at("criteria").at("rmax_m"));
  r.verify_p_joint = number(j.at("criteria").at("verify_p_joint"));
  r.validate_p_joint = number(j.at("criteria").at("validate_p_joint"));
  r.verify_go = j.at("criteria").at("verify_go").get<bool>();
  r.score.time = error_from_json(j.at("time"));
  r.score.radius = error_from_json(j.at("radius"));
  r.score.joint = error_from_json(j.at("joint"));
  r.score.overconfident_go_cells = j.at("overconfident_go_cells").get<std::size_t>();
  for (const nlohmann::json& c : j.at("overconfident_worst")) {
    r.score.overconfident.push_back({number(c.at("tmax_s")), number(c.at("rmax_m")), number(c.at("verify")),
                                     number(c.at("validate")), number(c.at("ci_low")), number(c.at("ci_high"))});
  }
  if (j.contains("separation") && !j.at("separation").is_null()) {
    SeparationScore sep;
    sep.error = error_from_json(j.at("separation"));
    sep.range = j.at("separation").at("d_range").get<std::string>();
    sep.overconfident_points = j.at("separation").at("overconfident_points").get<std::size_t>();
    r.separation = sep;
  }
  if (j.contains("robot_distances")) {  // absent in files written before it
    for (const nlohmann::json& d : j.at("robot_distances")) {
      r.robot_distances.push_back({d.at("name").get<std::string>(), number(d.at("verify_mean_m")),
                                   number(d.at("verify_sd_m")), number(d.at("validate_mean_m")),
                                   number(d.at("validate_sd_m")), d.at("comparable").get<bool>()});
    }
  }
  r.calibrate_s = number(j.at("seconds").at("calibrate"));
  r.validate_s = number(j.at("seconds").at("validate"));
  r.verify_s = number(j.at("seconds").at("verify"));
  // Results written before scoring had its own figure have none.
  if (j.at("seconds").contains("score")) r.score_s = number(j.at("seconds").at("score"));
  r.folder = j.at("folder").get<std::string>();
  r.reproduce = j.at("reproduce").get<std::string>();
  return r;
}

Json summary_json(const CampaignSummary& s, const Bounds& b) {
  Json j;
  j["missions"] = s.missions;
  j["scored"] = s.scored;
  j["could_not_run"] = s.could_not_run;
  j["not_evaluable"] = s.not_evaluable;
  j["runs"] = s.runs;
  j["bounds"] = {{"time", b.time}, {"radius", b.radius}, {"joint", b.joint}};
  j["time"] = {{"strict", stats_json(s.time_strict)}, {"tolerant", stats_json(s.time_tolerant)}};
  j["radius"] = {{"strict", stats_json(s.radius_strict)}, {"tolerant", stats_json(s.radius_tolerant)}};
  j["joint"] = {{"strict", stats_json(s.joint_strict)}, {"tolerant", stats_json(s.joint_tolerant)}};
  j["all_within_strict"] = s.all_within_strict;
  j["all_within_tolerant"] = s.all_within_tolerant;
  j["overconfident_go_cells"] = s.overconfident_cells;
  j["overconfident_go_missions"] = s.overconfident_missions;
  j["overconfident_go_cells_not_evaluable"] = s.overconfident_cells_not_evaluable;
  j["separation"] = {{"strict", stats_json(s.separation_strict)}, {"tolerant", stats_json(s.separation_tolerant)},
                     {"overconfident_points", s.separation_overconfident_points},
                     {"overconfident_missions", s.separation_overconfident_missions}};
  const CampaignSummary::RobotDistances& d = s.robot_distances;
  j["robot_distances"] = {{"robots", d.robots},
                          {"sd_ratio", {{"p10", d.sd_ratio_p10}, {"p50", d.sd_ratio_p50}, {"p90", d.sd_ratio_p90}}},
                          {"narrower_than_two_thirds", d.narrower},
                          {"wider_than_three_halves", d.wider},
                          {"mean_error_m", {{"p50", d.mean_error_p50_m}, {"p90", d.mean_error_p90_m},
                                            {"worst", d.mean_error_worst_m}}}};
  return j;
}

// The lines below were printf'd into fixed buffers, which cut a long error
// text; now built with the project's formatters (printf's conversions byte for
// byte, see number_format.hpp and text_columns.hpp), they are never cut.
std::string mission_line(const MissionResult& r, const Bounds& b) {
  const std::string name = left_aligned(r.name, 18);
  if (!r.error.empty()) return name + " could not run: " + r.error;
  const MissionScore& s = r.score;
  const char* verdict = s.within(b, false) ? "ok" : s.within(b, true) ? "ok within 1 %" : "FAIL";
  const auto pair = [](const ErrorSummary& e) { return format_fixed(e.strict, 3) + " / " + format_fixed(e.tolerant, 3); };
  return name + " " + std::to_string(r.robots) + " robot" + (r.robots == 1 ? " " : "s") + "  time " + pair(s.time) +
         "  radius " + pair(s.radius) + "  joint " + pair(s.joint) + "  over-confident GO " +
         std::to_string(s.overconfident_go_cells) + (r.evaluable ? "" : " (cannot evaluate)") + "  " + verdict +
         (r.separation ? "  apart " + pair(r.separation->error) +
                             (r.separation->overconfident_points ? " GO! " + std::to_string(r.separation->overconfident_points) : "")
                       : "");
}

std::string summary_text(const CampaignSummary& s, const Bounds& b) {
  std::string out = "missions " + std::to_string(s.missions) + ": scored " + std::to_string(s.scored) +
                    " (of which verify cannot evaluate " + std::to_string(s.not_evaluable) + "), could not run " +
                    std::to_string(s.could_not_run) + "; " + std::to_string(s.runs) + " validation runs\n";
  out += "max |verify - validate|     worst    p50    p90    p95   within bound\n";
  const auto row = [&](const char* what, const MetricStats& m, double bound) {
    const double pct = m.missions ? 100.0 * static_cast<double>(m.within) / static_cast<double>(m.missions) : 0.0;
    out += left_aligned(what, 26) + " " + format_fixed(m.worst, 3, 6) + " " + format_fixed(m.p50, 3, 6) + " " +
           format_fixed(m.p90, 3, 6) + " " + format_fixed(m.p95, 3, 6) + "   " + std::to_string(m.within) + " of " +
           std::to_string(m.missions) + " (" + format_fixed(pct, 0) + " %) <= " + format_fixed(bound, 2) + "\n";
  };
  row("time curve, strict", s.time_strict, b.time);
  row("time curve, 1 % shift", s.time_tolerant, b.time);
  row("radius curve, strict", s.radius_strict, b.radius);
  row("radius curve, 1 % shift", s.radius_tolerant, b.radius);
  row("joint surface, strict", s.joint_strict, b.joint);
  row("joint surface, 1 % shift", s.joint_tolerant, b.joint);
  const auto pct = [&s](std::size_t k) { return s.scored ? 100.0 * static_cast<double>(k) / static_cast<double>(s.scored) : 0.0; };
  out += "all three within " + format_fixed(b.time, 2) + "/" + format_fixed(b.radius, 2) + "/" + format_fixed(b.joint, 2) +
         ": strict " + std::to_string(s.all_within_strict) + " of " + std::to_string(s.scored) + " (" +
         format_fixed(pct(s.all_within_strict), 0) + " %), with the 1 % shift " + std::to_string(s.all_within_tolerant) +
         " (" + format_fixed(pct(s.all_within_tolerant), 0) + " %)\n";
  out += "over-confident GO cells (verify >= 0.8, validation's 95 % interval below 0.78): " +
         std::to_string(s.overconfident_cells) + " on " + std::to_string(s.overconfident_missions) +
         " evaluable missions; " + std::to_string(s.overconfident_cells_not_evaluable) +
         " more on missions verify cannot evaluate\n";
  const CampaignSummary::RobotDistances& d = s.robot_distances;
  if (d.robots > 0) {
    out += "final distance per robot (" + std::to_string(d.robots) +
           " comparable robots): verify's sd / the runs' p10 " + format_fixed(d.sd_ratio_p10, 2) + ", median " +
           format_fixed(d.sd_ratio_p50, 2) + ", p90 " + format_fixed(d.sd_ratio_p90, 2) + "; under 2/3 " +
           std::to_string(d.narrower) + ", over 3/2 " + std::to_string(d.wider) + "; |mean difference| median " +
           format_fixed(1000.0 * d.mean_error_p50_m, 1) + " mm, p90 " + format_fixed(1000.0 * d.mean_error_p90_m, 1) +
           " mm, worst " + format_fixed(1000.0 * d.mean_error_worst_m, 1) + " mm\n";
  }
  if (s.separation_strict.missions > 0) {
    out += "closest approach: P(no two robots ever within d), on the " + std::to_string(s.separation_strict.missions) +
           " missions whose runs come within 3 m\n";
    row("separation curve, strict", s.separation_strict, b.radius);
    row("separation curve, 1 % shift", s.separation_tolerant, b.radius);
    out += "over-confident separation points (verify >= 0.8, validation's 95 % interval below 0.78): " +
           std::to_string(s.separation_overconfident_points) + " on " + std::to_string(s.separation_overconfident_missions) +
           " missions\n";
  }
  return out;
}

}  // namespace p3at::crosscheck
