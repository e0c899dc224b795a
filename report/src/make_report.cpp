// vipars report --verify FILE.json --validate FILE.json --out DIR [options]
// vipars report MISSION --models FILE --world FILE --trials N
//   --tmax-range A:B:STEP --rmax-range A:B:STEP --out DIR [options]
// The verification-against-validation report (the seed paper's Figs. 9–13
// and the error map): data files, gnuplot figures (PNG and SVG), errors.json
// and a one-page index.html. docs/report.md.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "p3at/common/vipars_exit.hpp"
#include "p3at/report/make_report.hpp"
#include "p3at/report/report_build.hpp"
#include "p3at/report/command_lines.hpp"
#include "p3at/report/report_data.hpp"
#include "p3at/report/report_run.hpp"

namespace p3at::vipars {
namespace {


void progress(const std::string& line) { std::fprintf(stderr, "vipars report: %s\n", line.c_str()); }

int fail(const Error& e) {
  std::fprintf(stderr, "vipars report: %s\n", e.message.c_str());
  // Bad documents, flags and files are the user's to fix (2); anything else
  // (a folder that cannot be written, gnuplot failing) stopped the report (3).
  return e.code == Error::Code::invalid_argument || e.code == Error::Code::not_found ? kExitBadInput : kExitFailed;
}

int bad_input(const std::string& message) { return fail(make_error(Error::Code::invalid_argument, message)); }

Status write_json(const std::string& path, const nlohmann::ordered_json& doc) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << doc.dump(2) << "\n";
  out.close();
  if (!out) return make_error(Error::Code::io, path + ": cannot write");
  return {};
}

std::string numbers(const std::vector<double>& values) {
  std::string s;
  for (const double v : values) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.15g", v);
    s += (s.empty() ? "" : ",") + std::string(buf);
  }
  return s;
}

/// This report's own command line, from the flags (for the page).
std::string report_command_line(const ReportFlags& f, bool run_here) {
  std::vector<std::string> w{"vipars", "report"};
  const auto add = [&w](const std::string& flag, const std::string& value) {
    if (!value.empty()) w.insert(w.end(), {flag, value});
  };
  if (run_here) {
    w.push_back(f.mission_positional);
    add("--models", f.models_file);
    add("--world", f.world_file);
    add("--trials", std::to_string(f.trials));
    if (f.jobs) add("--jobs", std::to_string(f.jobs));
    add("--seed", std::to_string(f.seed));
    if (f.tmax_s) add("--tmax", numbers({*f.tmax_s}));
    if (f.rmax_m) add("--rmax", numbers({*f.rmax_m}));
    add("--tmax-range", f.tmax_range);
    add("--rmax-range", f.rmax_range);
  } else {
    add("--verify", f.verify_file);
    add("--validate", f.validate_file);
    add("--mission", f.mission_file);
    add("--models", f.models_file);
    add("--world", f.world_file);
  }
  add("--out", f.out_dir);
  add("--title", f.title);
  if (f.region_low != 0.05) add("--region-low", numbers({f.region_low}));
  if (f.region_high != 0.95) add("--region-high", numbers({f.region_high}));
  add("--rmax-slices", numbers(f.rmax_slices));
  add("--tmax-slices", numbers(f.tmax_slices));
  if (f.no_plots) w.push_back("--no-plots");
  return report::shell_join(w);
}

void print_summary(const report::Comparison& c, const std::string& out_dir) {
  const auto line = [](const char* name, const report::ErrorSummary& e) {
    std::string where;
    char buf[64];
    if (e.at_tmax_s) {
      std::snprintf(buf, sizeof buf, "Tmax %g s", *e.at_tmax_s);
      where += buf;
    }
    if (e.at_rmax_m) {
      std::snprintf(buf, sizeof buf, "%sRmax %g m", where.empty() ? "" : ", ", *e.at_rmax_m);
      where += buf;
    }
    std::printf("  %-26s max |verify - validate| %.4f at %-22s (verify %.4f, validate %.4f; bound %g) %s\n", name,
                e.max, where.c_str(), e.verify, e.validate, e.limit, e.pass() ? "PASS" : "FAIL");
  };
  std::printf("report in %s/index.html\n", out_dir.c_str());
  line("P(t <= Tmax) curve", c.time);
  line("P(every r <= Rmax) curve", c.radius);
  line("joint surface", c.joint);
}

}  // namespace

int run_report(ReportFlags f) {
  const bool run_here = !f.mission_positional.empty();
  report::BuildOptions o;
  o.out_dir = f.out_dir;
  o.title = f.title;
  o.gnuplot = f.gnuplot;
  o.render = !f.no_plots;
  o.thresholds = {f.region_low, f.region_high};
  o.rmax_slices = f.rmax_slices;
  o.tmax_slices = f.tmax_slices;
  std::string verify_path = f.verify_file, validate_path = f.validate_file;

  if (run_here) {
    if (!f.verify_file.empty() || !f.validate_file.empty()) {
      return bad_input("give either MISSION (to run both here) or --verify and --validate (documents), not both");
    }
    for (auto [flag, value] : {std::pair{"--models", &f.models_file}, std::pair{"--world", &f.world_file}}) {
      if (value->empty()) return bad_input(std::string(flag) + ": required with MISSION");
    }
    if (f.trials == 0) return bad_input("--trials: required with MISSION (1..1000000)");
    report::RunRequest r;
    r.mission_file = f.mission_positional;
    r.models_file = f.models_file;
    r.world_file = f.world_file;
    r.trials = f.trials;
    r.jobs = f.jobs;
    r.seed = f.seed;
    r.timeout_s = f.timeout_s;
    r.tmax_s = f.tmax_s;
    r.rmax_m = f.rmax_m;
    r.tmax_range = f.tmax_range;
    r.rmax_range = f.rmax_range;
    r.thresholds = o.thresholds;
    Result<report::RunOutput> ran = report::run_verify_and_validate(r, progress);
    if (!ran) return fail(ran.error());
    // The report is then built from these files, exactly as from documents given with --verify/--validate.
    std::error_code ec;
    std::filesystem::create_directories(f.out_dir, ec);
    if (ec) return fail(make_error(Error::Code::io, f.out_dir + ": cannot create the folder: " + ec.message()));
    verify_path = f.out_dir + "/verify.json";
    validate_path = f.out_dir + "/validate.json";
    if (Status s = write_json(verify_path, ran->verification); !s) return fail(s.error());
    if (Status s = write_json(validate_path, ran->validation); !s) return fail(s.error());
    progress("wrote " + verify_path + " and " + validate_path);
    char note[256];
    std::snprintf(note, sizeof note,
                  "Made in one run: the verification took %.3f s, the validation's %llu runs %.1f s on %u thread(s) "
                  "(%.1f runs/s).",
                  ran->verify_wall_s, static_cast<unsigned long long>(f.trials), ran->validate_wall_s, ran->jobs,
                  static_cast<double>(f.trials) / std::max(ran->validate_wall_s, 1e-9));
    o.notes.emplace_back(note);
    o.input_files = {{"mission (MISSION)", f.mission_positional},
                     {"robot models (--models)", f.models_file},
                     {"world (--world)", f.world_file}};
  } else {
    if (f.verify_file.empty() || f.validate_file.empty()) {
      return bad_input(
          "give --verify FILE.json and --validate FILE.json (or MISSION with --models, --world, --trials "
          "and the ranges to run both here)");
    }
    // Flags that only make sense when running here would otherwise be silently ignored.
    if (f.trials != 0 || !f.tmax_range.empty() || !f.rmax_range.empty() || f.tmax_s || f.rmax_m) {
      return bad_input(
          "--trials, --tmax, --rmax, --tmax-range and --rmax-range are for MISSION (running both here); "
          "with --verify and --validate the documents say them");
    }
  }

  Result<report::Side> v = report::load_side(verify_path);
  if (!v) return fail(v.error());
  Result<report::Side> w = report::load_side(validate_path);
  if (!w) return fail(w.error());

  o.input_files.insert(o.input_files.begin(),
                       {{run_here ? "verification (made here)" : "verification (--verify)", verify_path},
                        {run_here ? "validation (made here)" : "validation (--validate)", validate_path}});
  if (!run_here) {
    for (auto [role, path] :
         {std::pair{"mission (--mission)", &f.mission_file}, std::pair{"robot models (--models)", &f.models_file},
          std::pair{"world (--world)", &f.world_file}}) {
      if (!path->empty()) o.input_files.emplace_back(role, *path);
    }
    // The validation names its mission and world; hash them too when they are
    // here and were not given (a report made elsewhere simply lists fewer).
    for (auto [role, named, given] : {std::tuple{"mission (named in the validation)", w->mission_file, f.mission_file},
                                      std::tuple{"world (named in the validation)", w->world_file, f.world_file}}) {
      if (named && given.empty() && std::ifstream(*named).good()) o.input_files.emplace_back(role, *named);
    }
  }
  const std::string mission_for_verify = f.mission_file.empty() ? w->mission_file.value_or("") : f.mission_file;
  const auto command = [](const std::optional<std::string>& own, const std::string& flag, std::string rebuilt) {
    if (own) return *own;
    if (!flag.empty()) return flag;
    return rebuilt + "\n# rebuilt from the JSON document: flags it does not record (e.g. --criterion) are not shown";
  };
  o.commands = {{"verification", command(v->command, f.verify_command,
                                         report::verify_command(*v, mission_for_verify, f.models_file, verify_path))},
                {"validation", command(w->command, f.validate_command, report::validate_command(*w, validate_path))},
                {"this report", report_command_line(f, run_here)}};

  Result<report::Comparison> c = report::build_report(*v, *w, o, progress);
  if (!c) return fail(c.error());
  print_summary(*c, f.out_dir);
  return c->pass() ? kExitOk : kExitNoGo;
}

}  // namespace p3at::vipars
