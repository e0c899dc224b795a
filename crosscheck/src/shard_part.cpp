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
      MissionResult r = mission_result_from_json(nlohmann::json::parse(lines.next_line()));
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
