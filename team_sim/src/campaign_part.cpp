#include "p3at/team_sim/campaign_part.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <ostream>
#include <sstream>
#include <system_error>
#include <utility>

#include "p3at/common/number_format.hpp"
#include "p3at/team_sim/empirical.hpp"
#include "p3at/common/file_bytes.hpp"
#include "p3at/team_sim/part_file.hpp"
#include "p3at/team_sim/run_seed.hpp"

namespace p3at::team_sim {
namespace {

constexpr std::string_view kMagic = "vipars-validation-part";
// 2: a successful run's distances are where each robot came to rest after
// entering its final state. Version 1 parts recorded them where the run
// stopped (a robot alone at the cycle its last trigger fired, 3-33 cm short
// of where it stops), so their runs are not comparable and are refused.
constexpr int kVersion = 2;

Error invalid(std::string message) { return make_error(Error::Code::invalid_argument, std::move(message)); }

// ---- numbers and text fields ----

// Fields are tab-separated and records end at a newline, so a text field
// (an outcome with its reason, a path, a name) escapes those and '\'.
std::string escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '\\': out += "\\\\"; break;
      case '\t': out += "\\t"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      default: out += c;
    }
  }
  return out;
}

std::optional<std::string> unescape(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\') {
      out += text[i];
      continue;
    }
    if (++i == text.size()) return std::nullopt;
    switch (text[i]) {
      case '\\': out += '\\'; break;
      case 't': out += '\t'; break;
      case 'n': out += '\n'; break;
      case 'r': out += '\r'; break;
      default: return std::nullopt;
    }
  }
  return out;
}

bool is_hex64(std::string_view s) {
  return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

// ---- writing ----

template <class T, class F>
std::string list(const std::vector<T>& values, F&& format) {
  std::string out = std::to_string(values.size());
  for (const auto& v : values) out += "\t" + format(v);
  return out;
}

std::string counts_list(const std::vector<std::uint64_t>& v) {
  return list(v, [](std::uint64_t c) { return std::to_string(c); });
}
std::string reals_list(const std::vector<double>& v) { return list(v, format_shortest); }

std::string run_line(const RunResult& run) {
  std::string line = "run\t" + std::to_string(run.run) + "\t" + std::to_string(run.seed) + "\t" +
                     format_shortest(run.time_s) + "\t" + format_shortest(run.closest_approach_m);
  for (const auto& r : run.robots) line += "\t" + escape(r.phase) + "\t" + format_shortest(r.dist_to_goal_m);
  return line + "\t" + escape(run.outcome);
}

// ---- reading: one line at a time, errors name the file and line ----

std::optional<std::uint64_t> parse_count(std::string_view s) {
  std::uint64_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

std::optional<double> parse_real(std::string_view s) {
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

Result<std::uint64_t> count_field(const PartLines& lines, std::string_view what, std::string_view s) {
  auto v = parse_count(s);
  if (!v) return lines.error(std::string(what) + ": expected a whole number, got " + shown(s));
  return *v;
}

Result<double> real_field(const PartLines& lines, std::string_view what, std::string_view s) {
  auto v = parse_real(s);
  if (!v) return lines.error(std::string(what) + ": expected a number, got " + shown(s));
  return *v;
}

Result<std::string> text_field(const PartLines& lines, std::string_view what, std::string_view s) {
  auto v = unescape(s);
  if (!v) return lines.error(std::string(what) + ": bad escape in " + shown(s));
  return *v;
}

// `key<TAB>n<TAB>v1 ... vn`
template <class T, class F>
Result<std::vector<T>> expect_list(PartLines& lines, std::string_view key, F&& parse_one) {
  auto fields = expect_line(lines, key, -1);
  if (!fields) return fields.error();
  if (fields->empty()) return lines.error("'" + std::string(key) + "': expected a count of values");
  auto n = count_field(lines, std::string(key) + " count", (*fields)[0]);
  if (!n) return n.error();
  if (*n != fields->size() - 1) {
    return lines.error("'" + std::string(key) + "': says " + std::to_string(*n) + " value(s), has " +
                       std::to_string(fields->size() - 1));
  }
  std::vector<T> out;
  for (std::size_t i = 1; i < fields->size(); ++i) {
    auto v = parse_one(lines, std::string(key), (*fields)[i]);
    if (!v) return v.error();
    out.push_back(std::move(v).value());
  }
  return out;
}

#define P3AT_TRY_ASSIGN(target, expr) \
  do {                                \
    auto try_value_ = (expr);         \
    if (!try_value_) return try_value_.error(); \
    target = std::move(try_value_).value();     \
  } while (false)

Result<CampaignHeader> parse_header(PartLines& lines, Shard& shard, RunRange& range) {
  CampaignHeader h;
  std::vector<std::string_view> f;
  P3AT_TRY_ASSIGN(f, expect_line(lines, "content_hash", 1));
  if (!is_hex64(f[0])) return lines.error("content_hash: expected 64 lowercase hex digits, got " + shown(f[0]));
  h.content_hash = std::string(f[0]);
  P3AT_TRY_ASSIGN(f, expect_line(lines, "seed", 1));
  P3AT_TRY_ASSIGN(h.seed, count_field(lines, "seed", f[0]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "trials", 1));
  P3AT_TRY_ASSIGN(h.trials, count_field(lines, "trials", f[0]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "shard", 2));
  P3AT_TRY_ASSIGN(shard.index, count_field(lines, "shard index", f[0]));
  P3AT_TRY_ASSIGN(shard.count, count_field(lines, "shard count", f[1]));
  if (shard.count < 1 || shard.index >= shard.count || shard.count > h.trials) {
    return lines.error("shard: expected I N with 0 <= I < N <= trials (" + std::to_string(h.trials) + "), got " +
                       std::to_string(shard.index) + " " + std::to_string(shard.count));
  }
  P3AT_TRY_ASSIGN(f, expect_line(lines, "runs", 2));
  P3AT_TRY_ASSIGN(range.first, count_field(lines, "runs first", f[0]));
  P3AT_TRY_ASSIGN(range.end, count_field(lines, "runs end", f[1]));
  const RunRange expected = shard_runs(h.trials, shard);
  if (range.first != expected.first || range.end != expected.end) {
    return lines.error("runs: shard " + to_string(shard) + " of " + std::to_string(h.trials) + " trials is runs " +
                       std::to_string(expected.first) + " " + std::to_string(expected.end) + ", the file says " +
                       std::to_string(range.first) + " " + std::to_string(range.end));
  }
  P3AT_TRY_ASSIGN(f, expect_line(lines, "timeout_s", 1));
  P3AT_TRY_ASSIGN(h.timeout_s, real_field(lines, "timeout_s", f[0]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "point", 2));
  P3AT_TRY_ASSIGN(h.tmax_s, real_field(lines, "point tmax_s", f[0]));
  P3AT_TRY_ASSIGN(h.rmax_m, real_field(lines, "point rmax_m", f[1]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "grid", 1));
  if (f[0] != "0" && f[0] != "1") return lines.error("grid: expected 0 or 1, got " + shown(f[0]));
  h.has_grid = f[0] == "1";
  P3AT_TRY_ASSIGN(h.tmax_axis, expect_list<double>(lines, "tmax_axis", real_field));
  P3AT_TRY_ASSIGN(h.rmax_axis, expect_list<double>(lines, "rmax_axis", real_field));
  if (h.tmax_axis.empty() || h.rmax_axis.empty()) return lines.error("a grid axis has no values");
  P3AT_TRY_ASSIGN(f, expect_line(lines, "regions", 2));
  P3AT_TRY_ASSIGN(h.region_low, real_field(lines, "regions low", f[0]));
  P3AT_TRY_ASSIGN(h.region_high, real_field(lines, "regions high", f[1]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "mission", 1));
  P3AT_TRY_ASSIGN(h.mission_name, text_field(lines, "mission", f[0]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "threshold", 1));
  P3AT_TRY_ASSIGN(h.threshold, real_field(lines, "threshold", f[0]));
  P3AT_TRY_ASSIGN(h.robots, expect_list<std::string>(lines, "robots", text_field));
  if (h.robots.empty()) return lines.error("robots: expected at least one robot");
  P3AT_TRY_ASSIGN(f, expect_line(lines, "mission_file", 1));
  P3AT_TRY_ASSIGN(h.mission_file, text_field(lines, "mission_file", f[0]));
  P3AT_TRY_ASSIGN(f, expect_line(lines, "world_file", 1));
  P3AT_TRY_ASSIGN(h.world_file, text_field(lines, "world_file", f[0]));
  return h;
}

Result<PartCounts> parse_counts(PartLines& lines, const CampaignHeader& h) {
  PartCounts c;
  std::vector<std::string_view> f;
  P3AT_TRY_ASSIGN(f, expect_line(lines, "counts", 5));
  P3AT_TRY_ASSIGN(c.runs, count_field(lines, "counts runs", f[0]));
  P3AT_TRY_ASSIGN(c.failed, count_field(lines, "counts failed", f[1]));
  P3AT_TRY_ASSIGN(c.time, count_field(lines, "counts time", f[2]));
  P3AT_TRY_ASSIGN(c.radius, count_field(lines, "counts radius", f[3]));
  P3AT_TRY_ASSIGN(c.joint, count_field(lines, "counts joint", f[4]));
  P3AT_TRY_ASSIGN(c.robot_radius, expect_list<std::uint64_t>(lines, "robot_radius", count_field));
  P3AT_TRY_ASSIGN(c.grid_time, expect_list<std::uint64_t>(lines, "grid_time", count_field));
  P3AT_TRY_ASSIGN(c.grid_radius, expect_list<std::uint64_t>(lines, "grid_radius", count_field));
  P3AT_TRY_ASSIGN(c.grid_joint, expect_list<std::uint64_t>(lines, "grid_joint", count_field));
  if (c.robot_radius.size() != h.robots.size() || c.grid_time.size() != h.tmax_axis.size() ||
      c.grid_radius.size() != h.rmax_axis.size() || c.grid_joint.size() != h.tmax_axis.size() * h.rmax_axis.size()) {
    return lines.error("the counts do not have the shape of the robots and the grid axes above");
  }
  return c;
}

Result<RunResult> parse_run(PartLines& lines, const CampaignHeader& h, std::uint64_t expected_index) {
  if (lines.at_end()) return lines.error("expected 'run' " + std::to_string(expected_index) + ", got the end of the file");
  const auto f = lines.next();
  const std::size_t want = 5 + 2 * h.robots.size() + 1;
  if (f[0] != "run") return lines.error("expected 'run' " + std::to_string(expected_index) + ", got " + shown(f[0]));
  if (f.size() != want) {
    return lines.error("run: expected " + std::to_string(want - 1) + " values for " + std::to_string(h.robots.size()) +
                       " robot(s), got " + std::to_string(f.size() - 1));
  }
  RunResult run;
  P3AT_TRY_ASSIGN(run.run, count_field(lines, "run index", f[1]));
  if (run.run != expected_index) {
    return lines.error("run: expected run " + std::to_string(expected_index) + ", got run " + std::to_string(run.run));
  }
  P3AT_TRY_ASSIGN(run.seed, count_field(lines, "run seed", f[2]));
  if (run.seed != run_seed(h.seed, run.run)) {
    return lines.error("run " + std::to_string(run.run) + ": seed " + std::to_string(run.seed) +
                       " is not this campaign's (" + std::to_string(run_seed(h.seed, run.run)) + ")");
  }
  P3AT_TRY_ASSIGN(run.time_s, real_field(lines, "run time_s", f[3]));
  P3AT_TRY_ASSIGN(run.closest_approach_m, real_field(lines, "run closest_approach_m", f[4]));
  for (std::size_t i = 0; i < h.robots.size(); ++i) {
    RobotResult r;
    r.name = h.robots[i];
    P3AT_TRY_ASSIGN(r.phase, text_field(lines, "run phase", f[5 + 2 * i]));
    P3AT_TRY_ASSIGN(r.dist_to_goal_m, real_field(lines, "run distance", f[6 + 2 * i]));
    run.robots.push_back(std::move(r));
  }
  P3AT_TRY_ASSIGN(run.outcome, text_field(lines, "run outcome", f[want - 1]));
  if (run.outcome.empty()) return lines.error("run " + std::to_string(run.run) + ": empty outcome");
  return run;
}

#undef P3AT_TRY_ASSIGN

bool same_reals(const std::vector<double>& a, const std::vector<double>& b) {
  // Bitwise (through the text that reads back exactly): the same grid, not a nearby one.
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (format_shortest(a[i]) != format_shortest(b[i])) return false;
  }
  return true;
}

std::string reals_text(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + format_shortest(v[i]);
  return s + "]";
}

}  // namespace

// ---- shards ----

Result<Shard> parse_shard(std::string_view text) {
  const auto fail = [&] {
    return invalid("expected I/N with 0 <= I < N <= " + std::to_string(kMaxShards) + " (shard I of N, from 0), got '" +
                   std::string(text) + "'");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) return fail();
  const auto index = parse_count(text.substr(0, slash));
  const auto count = parse_count(text.substr(slash + 1));
  if (!index || !count || *count < 1 || *count > kMaxShards || *index >= *count) return fail();
  return Shard{*index, *count};
}

std::string to_string(const Shard& shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

RunRange shard_runs(std::uint64_t trials, const Shard& shard) {
  // trials <= 1e6 and count <= 1e5: the products fit in 64 bits.
  return RunRange{shard.index * trials / shard.count, (shard.index + 1) * trials / shard.count};
}

std::string range_text(const RunRange& r) {
  return r.size() == 0 ? "none" : std::to_string(r.first) + ".." + std::to_string(r.end - 1);
}

std::optional<std::string> shard_set_problem(const std::vector<FileShard>& sorted, std::uint64_t items,
                                             std::string_view counted) {
  const std::string what(counted);
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i].shard.index == sorted[i - 1].shard.index) {
      return sorted[i].file + " and " + sorted[i - 1].file + " are both shard " + to_string(sorted[i].shard) + " (" +
             what + " " + range_text(shard_runs(items, sorted[i].shard)) + " twice): give each shard once";
    }
  }
  if (sorted.empty()) return std::nullopt;
  const std::uint64_t n = sorted.front().shard.count;
  std::vector<Shard> missing;
  std::size_t next = 0;
  for (std::uint64_t s = 0; s < n; ++s) {
    if (next < sorted.size() && sorted[next].shard.index == s) {
      ++next;
    } else {
      missing.push_back({s, n});
    }
  }
  if (missing.empty()) return std::nullopt;
  std::string message = "missing " + std::to_string(missing.size()) + " of " + std::to_string(n) + " shards: ";
  for (std::size_t i = 0; i < missing.size() && i < 20; ++i) {
    message += (i ? ", " : "") + std::string("shard ") + to_string(missing[i]) + " (" + what + " " +
               range_text(shard_runs(items, missing[i])) + ")";
  }
  if (missing.size() > 20) message += ", ...";
  message += missing.size() == 1 ? "; rerun it with --shard " + to_string(missing.front())
                                 : "; rerun each with its --shard I/" + std::to_string(n);
  message += " (the command line otherwise the same)";
  return message;
}

// ---- the campaign ----

std::optional<std::string> campaign_difference(const CampaignHeader& a, const CampaignHeader& b) {
  if (a.content_hash != b.content_hash) {
    return "mission/world content hash " + b.content_hash.substr(0, 16) + "... vs " + a.content_hash.substr(0, 16) +
           "... (another mission or world file, or an edited one)";
  }
  if (a.seed != b.seed) return "seed " + std::to_string(b.seed) + " vs " + std::to_string(a.seed);
  if (a.trials != b.trials) return "trials " + std::to_string(b.trials) + " vs " + std::to_string(a.trials);
  if (format_shortest(a.timeout_s) != format_shortest(b.timeout_s)) return "timeout " + format_shortest(b.timeout_s) + " s vs " + format_shortest(a.timeout_s) + " s";
  if (format_shortest(a.tmax_s) != format_shortest(b.tmax_s) || format_shortest(a.rmax_m) != format_shortest(b.rmax_m)) {
    return "criterion point (tmax " + format_shortest(b.tmax_s) + " s, rmax " + format_shortest(b.rmax_m) + " m) vs (tmax " + format_shortest(a.tmax_s) +
           " s, rmax " + format_shortest(a.rmax_m) + " m)";
  }
  if (a.has_grid != b.has_grid || !same_reals(a.tmax_axis, b.tmax_axis) || !same_reals(a.rmax_axis, b.rmax_axis)) {
    return "grid tmax " + reals_text(b.tmax_axis) + " rmax " + reals_text(b.rmax_axis) + " vs tmax " +
           reals_text(a.tmax_axis) + " rmax " + reals_text(a.rmax_axis);
  }
  if (format_shortest(a.region_low) != format_shortest(b.region_low) || format_shortest(a.region_high) != format_shortest(b.region_high)) {
    return "region bounds " + format_shortest(b.region_low) + ":" + format_shortest(b.region_high) + " vs " + format_shortest(a.region_low) + ":" +
           format_shortest(a.region_high);
  }
  if (a.mission_name != b.mission_name || a.robots != b.robots || format_shortest(a.threshold) != format_shortest(b.threshold)) {
    return "mission name, robots or threshold (same content hash: a damaged part)";
  }
  return std::nullopt;
}

PartCounts count_runs(const CampaignHeader& h, const std::vector<RunResult>& runs) {
  PartCounts c;
  const EmpiricalPoint point = empirical_at(runs, h.tmax_s, h.rmax_m);
  c.runs = point.runs;
  c.failed = point.failed_runs;
  c.time = point.time.count;
  c.radius = point.radius.count;
  c.joint = point.joint.count;
  c.robot_radius.assign(h.robots.size(), 0);
  for (std::size_t i = 0; i < point.robots.size() && i < c.robot_radius.size(); ++i) {
    c.robot_radius[i] = point.robots[i].radius.count;
  }
  const EmpiricalGrid grid = empirical_grid(runs, h.tmax_axis, h.rmax_axis);
  for (const auto& e : grid.time) c.grid_time.push_back(e.count);
  for (const auto& e : grid.radius) c.grid_radius.push_back(e.count);
  for (const auto& row : grid.joint) {
    for (const auto& e : row) c.grid_joint.push_back(e.count);
  }
  return c;
}

void add_counts(PartCounts& total, const PartCounts& part) {
  total.runs += part.runs;
  total.failed += part.failed;
  total.time += part.time;
  total.radius += part.radius;
  total.joint += part.joint;
  const auto add = [](std::vector<std::uint64_t>& to, const std::vector<std::uint64_t>& from) {
    if (to.size() < from.size()) to.resize(from.size(), 0);
    for (std::size_t i = 0; i < from.size(); ++i) to[i] += from[i];
  };
  add(total.robot_radius, part.robot_radius);
  add(total.grid_time, part.grid_time);
  add(total.grid_radius, part.grid_radius);
  add(total.grid_joint, part.grid_joint);
}

std::optional<std::string> counts_difference(const PartCounts& a, const PartCounts& b) {
  const auto one = [](const char* name, std::uint64_t x, std::uint64_t y) -> std::optional<std::string> {
    if (x == y) return std::nullopt;
    return std::string(name) + ": " + std::to_string(x) + " vs " + std::to_string(y);
  };
  const auto many = [](const char* name, const std::vector<std::uint64_t>& x,
                       const std::vector<std::uint64_t>& y) -> std::optional<std::string> {
    if (x == y) return std::nullopt;
    if (x.size() != y.size()) return std::string(name) + ": " + std::to_string(x.size()) + " vs " +
                                     std::to_string(y.size()) + " cells";
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i] != y[i]) {
        return std::string(name) + " cell " + std::to_string(i) + ": " + std::to_string(x[i]) + " vs " +
               std::to_string(y[i]);
      }
    }
    return std::nullopt;
  };
  for (auto d : {one("runs", a.runs, b.runs), one("failed", a.failed, b.failed), one("time", a.time, b.time),
                 one("radius", a.radius, b.radius), one("joint", a.joint, b.joint),
                 many("robot_radius", a.robot_radius, b.robot_radius), many("grid_time", a.grid_time, b.grid_time),
                 many("grid_radius", a.grid_radius, b.grid_radius), many("grid_joint", a.grid_joint, b.grid_joint)}) {
    if (d) return d;
  }
  return std::nullopt;
}

CampaignPart make_part(CampaignHeader header, const Shard& shard, std::vector<RunResult> runs) {
  CampaignPart part;
  part.header = std::move(header);
  part.shard = shard;
  part.range = shard_runs(part.header.trials, shard);
  part.runs = std::move(runs);
  part.counts = count_runs(part.header, part.runs);
  return part;
}

// ---- the file ----

void write_part(std::ostream& out, const CampaignPart& part) {
  const CampaignHeader& h = part.header;
  const PartCounts& c = part.counts;
  std::ostringstream body;
  body << kMagic << "\t" << kVersion << "\n"
       << "content_hash\t" << h.content_hash << "\n"
       << "seed\t" << h.seed << "\n"
       << "trials\t" << h.trials << "\n"
       << "shard\t" << part.shard.index << "\t" << part.shard.count << "\n"
       << "runs\t" << part.range.first << "\t" << part.range.end << "\n"
       << "timeout_s\t" << format_shortest(h.timeout_s) << "\n"
       << "point\t" << format_shortest(h.tmax_s) << "\t" << format_shortest(h.rmax_m) << "\n"
       << "grid\t" << (h.has_grid ? 1 : 0) << "\n"
       << "tmax_axis\t" << reals_list(h.tmax_axis) << "\n"
       << "rmax_axis\t" << reals_list(h.rmax_axis) << "\n"
       << "regions\t" << format_shortest(h.region_low) << "\t" << format_shortest(h.region_high) << "\n"
       << "mission\t" << escape(h.mission_name) << "\n"
       << "threshold\t" << format_shortest(h.threshold) << "\n"
       << "robots\t" << list(h.robots, [](const std::string& s) { return escape(s); }) << "\n"
       << "mission_file\t" << escape(h.mission_file) << "\n"
       << "world_file\t" << escape(h.world_file) << "\n"
       << "counts\t" << c.runs << "\t" << c.failed << "\t" << c.time << "\t" << c.radius << "\t" << c.joint << "\n"
       << "robot_radius\t" << counts_list(c.robot_radius) << "\n"
       << "grid_time\t" << counts_list(c.grid_time) << "\n"
       << "grid_radius\t" << counts_list(c.grid_radius) << "\n"
       << "grid_joint\t" << counts_list(c.grid_joint) << "\n";
  for (const auto& run : part.runs) body << run_line(run) << "\n";
  const std::string text = body.str();
  out << text << part_end_line(text, part.runs.size());
}

Status write_part_file(const std::string& path, const CampaignPart& part) {
  return write_file_whole(path, [&part](std::ostream& out) { write_part(out, part); });
}

Result<CampaignPart> parse_part(std::string_view text, const std::string& source) {
  // The checksum first: a part cut short or changed anywhere is refused as a
  // whole, before any of its numbers is believed.
  const auto checked = check_part(text, source, "runs");
  if (!checked) return checked.error();

  PartLines lines(checked->body, source);
  auto magic = lines.next();
  if (magic.size() != 2 || magic[0] != kMagic) {
    return lines.error("expected '" + std::string(kMagic) + "\t" + std::to_string(kVersion) + "', got " +
                       shown(magic[0]));
  }
  if (magic[1] == "1") {
    return lines.error("part format version 1, this vipars reads version " + std::to_string(kVersion) +
                       ": version 1 recorded a finished robot's distance where its last trigger fired, not where it "
                       "came to rest, so its runs cannot be counted with new ones; rerun its shard (or its runs)");
  }
  if (magic[1] != std::to_string(kVersion)) {
    return lines.error("part format version " + std::string(magic[1]) + ", this vipars reads version " +
                       std::to_string(kVersion));
  }
  CampaignPart part;
  auto header = parse_header(lines, part.shard, part.range);
  if (!header) return header.error();
  part.header = std::move(header).value();
  auto counts = parse_counts(lines, part.header);
  if (!counts) return counts.error();
  part.counts = std::move(counts).value();
  for (std::uint64_t i = part.range.first; i < part.range.end; ++i) {
    auto run = parse_run(lines, part.header, i);
    if (!run) return run.error();
    part.runs.push_back(std::move(run).value());
  }
  if (!lines.at_end()) return lines.error("expected the 'end' line after run " + std::to_string(part.range.end - 1));
  if (auto n = parse_count(checked->end_count); !n || *n != part.runs.size()) {
    return invalid(source + ": the end line counts " + std::string(checked->end_count) + " runs, the part has " +
                   std::to_string(part.runs.size()));
  }
  // The stored counts must be what the runs give: two records of one fact.
  if (auto d = counts_difference(part.counts, count_runs(part.header, part.runs))) {
    return invalid(source + ": its counts disagree with its runs (" + *d + ", stored vs recounted)");
  }
  return part;
}

Result<CampaignPart> read_part_file(const std::string& path) {
  auto text = read_file_bytes(path);
  if (!text) return text.error();
  return parse_part(*text, path);
}

// ---- merging ----

Result<MergedCampaign> merge_parts(std::vector<NamedPart> parts) {
  if (parts.empty()) return invalid("no parts to merge");
  // Shard order, whatever order the files were given in.
  std::stable_sort(parts.begin(), parts.end(),
                   [](const NamedPart& a, const NamedPart& b) { return a.part.shard.index < b.part.shard.index; });
  const NamedPart& first = parts.front();
  for (const NamedPart& p : parts) {
    if (auto d = campaign_difference(first.part.header, p.part.header)) {
      return invalid(p.file + ": not a part of the same campaign as " + first.file + ": " + *d);
    }
    if (p.part.shard.count != first.part.shard.count) {
      return invalid(p.file + ": shard " + to_string(p.part.shard) + " of a campaign cut into " +
                     std::to_string(p.part.shard.count) + " shards, " + first.file + " is of one cut into " +
                     std::to_string(first.part.shard.count));
    }
  }
  const std::uint64_t n = first.part.shard.count;
  const std::uint64_t trials = first.part.header.trials;
  std::vector<FileShard> shards;
  for (const NamedPart& p : parts) shards.push_back({p.file, p.part.shard});
  if (auto problem = shard_set_problem(shards, trials, "runs")) return invalid(*problem);

  MergedCampaign merged;
  merged.header = first.part.header;
  merged.shard_count = n;
  merged.runs.reserve(trials);
  for (NamedPart& p : parts) {
    add_counts(merged.counts, p.part.counts);
    for (auto& run : p.part.runs) merged.runs.push_back(std::move(run));
  }
  // Each part's counts were checked against its runs when read; the sum must
  // then be the whole campaign's counts. Checked anyway: it is cheap.
  if (auto d = counts_difference(merged.counts, count_runs(merged.header, merged.runs))) {
    return make_error(Error::Code::state, "the parts' summed counts disagree with their runs (" + *d + ")");
  }
  if (merged.runs.size() != trials) {
    return make_error(Error::Code::state, "merged " + std::to_string(merged.runs.size()) + " runs of " +
                                              std::to_string(trials) + " expected");
  }
  return merged;
}

}  // namespace p3at::team_sim
