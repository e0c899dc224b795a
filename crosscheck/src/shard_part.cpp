// A cross-check campaign's shard part and merging the parts (shard_part.hpp).

#include "p3at/crosscheck/shard_part.hpp"

#include "p3at/common/file_bytes.hpp"

#include <algorithm>
#include <limits>
#include <ostream>
#include <utility>

#include "p3at/crosscheck/result_json.hpp"

namespace p3at::crosscheck {
namespace {

using Json = nlohmann::ordered_json;
constexpr std::string_view kMagic = "vipars-crosscheck-part\t1";

Error invalid(std::string message) { return make_error(Error::Code::invalid_argument, std::move(message)); }

// Length-prefixed, so no two different inputs give the same bytes.
void put(std::string& out, std::string_view part) { out += std::to_string(part.size()) + ":" + std::string(part) + ";"; }

double real(const Json& j) { return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>(); }

ErrorSummary error_from_json(const Json& j) {
  ErrorSummary e;
  e.strict = real(j.at("strict"));
  e.tolerant = real(j.at("tolerant"));
  const Json& s = j.at("strict_at");
  e.strict_at_tmax_s = real(s.at("tmax_s"));
  e.strict_at_rmax_m = real(s.at("rmax_m"));
  e.strict_verify = real(s.at("verify"));
  e.strict_validate = real(s.at("validate"));
  const Json& t = j.at("tolerant_at");
  e.tolerant_at_tmax_s = real(t.at("tmax_s"));
  e.tolerant_at_rmax_m = real(t.at("rmax_m"));
  e.tolerant_verify = real(t.at("verify"));
  e.tolerant_validate = real(t.at("validate"));
  e.points = j.at("points").get<std::size_t>();
  return e;
}

}  // namespace

std::string campaign_identity(const std::vector<MissionInput>& inputs, const CampaignOptions& o) {
  std::string bytes = "p3at-crosscheck-campaign-v1;";
  for (const MissionInput& m : inputs) {
    put(bytes, m.name);
    put(bytes, m.mission_yaml);
    put(bytes, m.world_yaml);
    put(bytes, m.models_yaml);
    put(bytes, m.generator_seed ? std::to_string(*m.generator_seed) : "-");
  }
  for (std::uint64_t v : {o.runs, o.seed, static_cast<std::uint64_t>(o.tmax_points),
                          static_cast<std::uint64_t>(o.rmax_points), static_cast<std::uint64_t>(o.calibration_runs),
                          static_cast<std::uint64_t>(o.calibration_messages)}) {
    put(bytes, std::to_string(v));
  }
  return team_sim::part_checksum(bytes);
}

MissionResult mission_result_from_json(const Json& j) {
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
  const Json& c = j.at("criteria");
  r.criteria_tmax_s = real(c.at("tmax_s"));
  r.criteria_rmax_m = real(c.at("rmax_m"));
  r.verify_p_joint = real(c.at("verify_p_joint"));
  r.validate_p_joint = real(c.at("validate_p_joint"));
  r.verify_go = c.at("verify_go").get<bool>();
  r.score.time = error_from_json(j.at("time"));
  r.score.radius = error_from_json(j.at("radius"));
  r.score.joint = error_from_json(j.at("joint"));
  r.score.overconfident_go_cells = j.at("overconfident_go_cells").get<std::size_t>();
  for (const Json& cell : j.at("overconfident_worst")) {
    OverconfidentCell o;
    o.tmax_s = real(cell.at("tmax_s"));
    o.rmax_m = real(cell.at("rmax_m"));
    o.verify = real(cell.at("verify"));
    o.validate = real(cell.at("validate"));
    o.ci_low = real(cell.at("ci_low"));
    o.ci_high = real(cell.at("ci_high"));
    r.score.overconfident.push_back(o);
  }
  const Json& s = j.at("seconds");
  r.calibrate_s = real(s.at("calibrate"));
  r.validate_s = real(s.at("validate"));
  r.verify_s = real(s.at("verify"));
  r.folder = j.at("folder").get<std::string>();
  r.reproduce = j.at("reproduce").get<std::string>();
  return r;
}

void write_crosscheck_part(std::ostream& out, const CrosscheckPart& part) {
  const CrosscheckPartHeader& h = part.header;
  Json header;
  header["identity"] = h.identity;
  header["command"] = h.command;
  header["names"] = h.names;
  header["shard"] = {h.shard.index, h.shard.count};
  header["missions"] = {h.missions.first, h.missions.end};
  header["outputs"] = {{"out_dir", h.out_dir}, {"gnuplot", h.gnuplot}, {"report", h.report},
                       {"baseline", h.baseline}, {"write_baseline", h.write_baseline},
                       {"baseline_margin", h.baseline_margin}, {"runs_per_mission", h.runs_per_mission},
                       {"seed", h.seed}};
  std::string body = std::string(kMagic) + "\n" + header.dump() + "\n";
  for (const MissionResult& r : part.results) body += mission_result_json(r).dump() + "\n";
  out << body << team_sim::part_end_line(body, part.results.size());
}

Status write_crosscheck_part_file(const std::string& path, const CrosscheckPart& part) {
  return team_sim::write_file_whole(path, [&part](std::ostream& out) { write_crosscheck_part(out, part); });
}

bool is_crosscheck_part(std::string_view text) { return text.substr(0, kMagic.size()) == kMagic; }

Result<CrosscheckPart> parse_crosscheck_part(std::string_view text, const std::string& source) {
  // The checksum first (team_sim's part file): a part cut short or changed
  // anywhere is refused as a whole.
  const auto checked = team_sim::check_part(text, source, "missions");
  if (!checked) return checked.error();
  team_sim::PartLines lines(checked->body, source);
  const std::size_t line_count = lines.count();
  if (line_count < 2 || lines.next_line() != kMagic) {
    return invalid(source + ":1: expected '" + std::string(kMagic.substr(0, kMagic.find('\t'))) + " 1'");
  }
  CrosscheckPart part;
  std::size_t line = 2;
  try {
    const Json header = Json::parse(lines.next_line());
    CrosscheckPartHeader& h = part.header;
    h.identity = header.at("identity").get<std::string>();
    h.command = header.at("command").get<std::string>();
    h.names = header.at("names").get<std::vector<std::string>>();
    h.shard.index = header.at("shard").at(0).get<std::uint64_t>();
    h.shard.count = header.at("shard").at(1).get<std::uint64_t>();
    h.missions.first = header.at("missions").at(0).get<std::uint64_t>();
    h.missions.end = header.at("missions").at(1).get<std::uint64_t>();
    const Json& outputs = header.at("outputs");
    h.out_dir = outputs.at("out_dir").get<std::string>();
    h.gnuplot = outputs.at("gnuplot").get<std::string>();
    h.report = outputs.at("report").get<bool>();
    h.baseline = outputs.at("baseline").get<std::string>();
    h.write_baseline = outputs.at("write_baseline").get<std::string>();
    h.baseline_margin = outputs.at("baseline_margin").get<double>();
    h.runs_per_mission = outputs.at("runs_per_mission").get<std::uint64_t>();
    h.seed = outputs.at("seed").get<std::uint64_t>();
    if (h.shard.count < 1 || h.shard.index >= h.shard.count || h.shard.count > h.names.size()) {
      return invalid(source + ":2: shard " + std::to_string(h.shard.index) + "/" + std::to_string(h.shard.count) +
                     " of " + std::to_string(h.names.size()) + " missions is not a shard");
    }
    const team_sim::RunRange expected = team_sim::shard_runs(h.names.size(), h.shard);
    if (expected.first != h.missions.first || expected.end != h.missions.end) {
      return invalid(source + ":2: shard " + team_sim::to_string(h.shard) + " is missions " + team_sim::range_text(expected) +
                     ", the part says " + team_sim::range_text(h.missions));
    }
    if (line_count - 2 != h.missions.size()) {
      return invalid(source + ": " + std::to_string(line_count - 2) + " mission results for shard " +
                     team_sim::to_string(h.shard) + "'s " + std::to_string(h.missions.size()) + " missions");
    }
    for (std::uint64_t i = h.missions.first; i < h.missions.end; ++i) {
      line = i - h.missions.first + 3;
      MissionResult r = mission_result_from_json(Json::parse(lines.next_line()));
      if (r.name != h.names[i]) {
        return invalid(source + ":" + std::to_string(line) + ": expected mission " + h.names[i] + ", got " + r.name);
      }
      part.results.push_back(std::move(r));
    }
  } catch (const std::exception& e) {
    return invalid(source + ":" + std::to_string(line) + ": " + e.what());
  }
  return part;
}

Result<CrosscheckPart> read_crosscheck_part_file(const std::string& path) {
  auto text = read_file_bytes(path);
  if (!text) return text.error();
  return parse_crosscheck_part(*text, path);
}

Result<MergedCrosscheck> merge_crosscheck_parts(std::vector<NamedCrosscheckPart> parts) {
  if (parts.empty()) return invalid("no parts to merge");
  std::stable_sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) {
    return a.part.header.shard.index < b.part.header.shard.index;
  });
  const NamedCrosscheckPart& first = parts.front();
  for (const NamedCrosscheckPart& p : parts) {
    const CrosscheckPartHeader& a = first.part.header;
    const CrosscheckPartHeader& b = p.part.header;
    if (a.identity != b.identity || a.names != b.names || a.command != b.command) {
      return invalid(p.file + ": not a part of the same campaign as " + first.file +
                     ": other missions, files or options (campaign identity " + b.identity.substr(0, 16) + "... vs " +
                     a.identity.substr(0, 16) + "...)");
    }
    if (b.shard.count != a.shard.count) {
      return invalid(p.file + ": shard " + team_sim::to_string(b.shard) + " of a campaign cut into " +
                     std::to_string(b.shard.count) + " shards, " + first.file + " is of one cut into " +
                     std::to_string(a.shard.count));
    }
  }
  std::vector<team_sim::FileShard> shards;
  for (const NamedCrosscheckPart& p : parts) shards.push_back({p.file, p.part.header.shard});
  if (auto problem = team_sim::shard_set_problem(shards, first.part.header.names.size(), "missions")) {
    return invalid(*problem);
  }
  MergedCrosscheck merged;
  merged.header = first.part.header;
  merged.command = first.part.header.command;
  merged.parts = parts.size();
  for (NamedCrosscheckPart& p : parts) {
    for (MissionResult& r : p.part.results) merged.results.push_back(std::move(r));
  }
  return merged;
}

}  // namespace p3at::crosscheck
