// The campaign's report (campaign_report.hpp): errors.dat, the two figures,
// the failing missions' pages (report::build_report, as `vipars report`
// makes them) and index.html.

#include "p3at/crosscheck/campaign_report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "p3at/common/number_format.hpp"
#include "p3at/report/report_build.hpp"
#include "p3at/report/report_data.hpp"

namespace p3at::crosscheck {
namespace fs = std::filesystem;

bool mission_fails(const MissionResult& r, const Bounds& b) {
  return !r.error.empty() || !r.score.within(b, true) || r.score.overconfident_go_cells > 0;
}

namespace {

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '&': o += "&amp;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

bool write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  out.close();
  return static_cast<bool>(out);
}

std::string run_gnuplot(const std::string& gnuplot, const fs::path& dir, const std::string& script) {
  const std::string cmd = "cd '" + dir.string() + "' && " + gnuplot + " '" + script + "' 2>&1";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "cannot run " + gnuplot;
  char buf[256];
  while (fgets(buf, sizeof buf, p)) out += buf;
  if (pclose(p) != 0) return gnuplot + " " + script + ": " + (out.empty() ? "failed" : out);
  return "";
}

// errors.dat: one row per scored mission; the CDF and the histogram read it.
std::string errors_dat(const std::vector<MissionResult>& results) {
  std::ostringstream d;
  d << "# name time_strict time_tolerant radius_strict radius_tolerant joint_strict joint_tolerant overconfident_go evaluable\n";
  for (const MissionResult& r : results) {
    if (!r.error.empty()) continue;
    d << r.name << ' ' << r.score.time.strict << ' ' << r.score.time.tolerant << ' ' << r.score.radius.strict << ' '
      << r.score.radius.tolerant << ' ' << r.score.joint.strict << ' ' << r.score.joint.tolerant << ' '
      << r.score.overconfident_go_cells << ' ' << (r.evaluable ? 1 : 0) << '\n';
  }
  return d.str();
}

std::string cdf_script(const Bounds& b, std::size_t n, const std::string& terminal, const std::string& out) {
  std::ostringstream s;
  s << "# The fraction of missions whose max |verify - validate| is at most x (`gnuplot errors_cdf.gp`).\n"
    << terminal << "\nset output '" << out << "'\n"
    << "set multiplot layout 1,3 title 'Cross-check: max |verify - validate| over " << n << " missions'\n"
    << "set xlabel 'max |verify - validate|'\nset ylabel 'fraction of missions'\nset yrange [0:1.02]\nset xrange [0:1]\n"
    << "set key bottom right\nset grid\n";
  const char* names[3] = {"time curve", "radius curve", "joint surface"};
  const double bounds[3] = {b.time, b.radius, b.joint};
  for (int k = 0; k < 3; ++k) {
    s << "set title '" << names[k] << "'\nset arrow 1 from " << bounds[k] << ",0 to " << bounds[k]
      << ",1 nohead dt 2 lc rgb 'gray30'\n"
      << "plot 'errors.dat' using " << 2 + 2 * k << ":(1.0/" << n << ") smooth cumulative with steps lw 2 lc rgb '#d62728' title 'strict', \\\n"
      << "     'errors.dat' using " << 3 + 2 * k << ":(1.0/" << n << ") smooth cumulative with steps lw 2 lc rgb '#1f77b4' title '1 % shift'\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

std::string hist_script(const Bounds& b, std::size_t n, const std::string& terminal, const std::string& out) {
  std::ostringstream s;
  s << "# How many missions have each max |verify - validate| (bins of 0.02; `gnuplot errors_hist.gp`).\n"
    << terminal << "\nset output '" << out << "'\nbin(x) = 0.02 * floor(x / 0.02) + 0.01\n"
    << "set multiplot layout 1,3 title 'Cross-check: errors over " << n << " missions (bins of 0.02)'\n"
    << "set xlabel 'max |verify - validate|'\nset ylabel 'missions'\nset style fill solid 0.5\nset boxwidth 0.009\n"
    << "set xrange [0:1]\nset key top right\nset grid\n";
  const char* names[3] = {"time curve", "radius curve", "joint surface"};
  const double bounds[3] = {b.time, b.radius, b.joint};
  for (int k = 0; k < 3; ++k) {
    s << "set title '" << names[k] << "'\nset arrow 1 from " << bounds[k] << ",graph 0 to " << bounds[k]
      << ",graph 1 nohead dt 2 lc rgb 'gray30'\n"
      << "plot 'errors.dat' using (bin($" << 2 + 2 * k << ")-0.0045):(1) smooth frequency with boxes lc rgb '#d62728' title 'strict', \\\n"
      << "     'errors.dat' using (bin($" << 3 + 2 * k << ")+0.0045):(1) smooth frequency with boxes lc rgb '#1f77b4' title '1 % shift'\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

// The mission's Figs. 9-14 page from its verify.json and validate.json.
std::string make_page(const MissionResult& r, const std::string& gnuplot) {
  namespace rep = vipars::report;
  const fs::path folder(r.folder);
  Result<rep::Side> v = rep::load_side((folder / "verify.json").string());
  if (!v) return v.error().message;
  Result<rep::Side> w = rep::load_side((folder / "validate.json").string());
  if (!w) return w.error().message;
  rep::BuildOptions o;
  o.out_dir = (folder / "page").string();
  o.title = r.name;
  o.gnuplot = gnuplot;
  for (const char* f : {"mission.yaml", "world.yaml", "models.yaml"}) {
    o.input_files.emplace_back(std::string(f).substr(0, std::string(f).find('.')), (folder / f).string());
  }
  o.commands.emplace_back("this mission's cross-check", r.reproduce);
  o.notes.push_back("Models: " + r.calibration_note);
  for (const std::string& a : r.approximations) o.notes.push_back("Verifier approximation: " + a);
  Result<rep::Comparison> built = rep::build_report(*v, *w, o);
  if (!built) return built.error().message;
  return "";
}

}  // namespace

std::vector<std::string> write_campaign_report(const std::vector<MissionResult>& results, const CampaignSummary& summary,
                                               const Bounds& b, const ReportOptions& o) {
  std::vector<std::string> problems;
  const fs::path dir(o.out_dir);
  if (!write_file(dir / "errors.dat", errors_dat(results))) problems.push_back("cannot write " + (dir / "errors.dat").string());
  const std::size_t n = std::max<std::size_t>(summary.scored, 1);
  const std::string png = "set terminal pngcairo size 1500,520 font ',10'";
  const std::string svg = "set terminal svg size 1500,520 dynamic font ',10'";
  write_file(dir / "errors_cdf.gp", cdf_script(b, n, png, "errors_cdf.png") + cdf_script(b, n, svg, "errors_cdf.svg"));
  write_file(dir / "errors_hist.gp", hist_script(b, n, png, "errors_hist.png") + hist_script(b, n, svg, "errors_hist.svg"));
  if (!o.gnuplot.empty() && summary.scored > 0) {
    for (const char* gp : {"errors_cdf.gp", "errors_hist.gp"}) {
      const std::string err = run_gnuplot(o.gnuplot, dir, gp);
      if (!err.empty()) problems.push_back(err);
    }
  }

  // Worst first: by the joint surface's shift-tolerant error, then the over-confident cells.
  std::vector<const MissionResult*> order;
  for (const MissionResult& r : results) order.push_back(&r);
  std::stable_sort(order.begin(), order.end(), [](const MissionResult* a, const MissionResult* c) {
    if (a->error.empty() != c->error.empty()) return !a->error.empty();
    const double ea = std::max({a->score.joint.tolerant, a->score.time.tolerant, a->score.radius.tolerant});
    const double ec = std::max({c->score.joint.tolerant, c->score.time.tolerant, c->score.radius.tolerant});
    if (ea != ec) return ea > ec;
    return a->score.overconfident_go_cells > c->score.overconfident_go_cells;
  });
  std::size_t pages = 0;
  std::vector<bool> has_page(results.size(), false);
  for (const MissionResult* r : order) {
    if (!r->error.empty() || !mission_fails(*r, b) || pages >= o.max_pages || o.gnuplot.empty()) continue;
    const std::string err = make_page(*r, o.gnuplot);
    if (!err.empty()) {
      problems.push_back(r->name + ": page: " + err);
    } else {
      has_page[static_cast<std::size_t>(r - results.data())] = true;
      ++pages;
    }
  }

  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Cross-check</title>\n"
    << "<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
       "padding:2px 6px;text-align:right}td.l{text-align:left}.bad{background:#fdd}.ok{background:#dfd}"
       "pre{background:#f6f6f6;padding:.5em}</style></head><body>\n"
    << "<h1>Cross-check: <code>vipars verify</code> against <code>vipars validate</code></h1>\n"
    << "<p>Command: <code>" << html_escape(o.command) << "</code> (docs/crosscheck.md says what each number means).</p>\n"
    << "<pre>" << html_escape(summary_text(summary, b)) << "</pre>\n"
    << "<p><a href=\"errors_cdf.svg\"><img src=\"errors_cdf.png\" width=\"1000\" alt=\"CDF of the errors\"></a></p>\n"
    << "<p><a href=\"errors_hist.svg\"><img src=\"errors_hist.png\" width=\"1000\" alt=\"histogram of the errors\"></a></p>\n"
    << "<h2>Missions, worst first</h2>\n<p>Errors are strict / with the 1 % shift; bounds " << b.time << " / " << b.radius
    << " / " << b.joint << ". A page (Figs. 9-14 of <code>vipars report</code>) for the " << o.max_pages
    << " worst failing missions.</p>\n<table><tr><th>mission</th><th>robots</th><th>time</th><th>radius</th><th>joint</th>"
       "<th>over-confident GO cells</th><th>verify can evaluate</th><th>verdict</th><th>files</th></tr>\n";
  for (const MissionResult* r : order) {
    const std::string base = "missions/" + r->name + "/";
    h << "<tr class=\"" << (mission_fails(*r, b) ? "bad" : "ok") << "\"><td class=\"l\">" << html_escape(r->name) << "</td>";
    if (!r->error.empty()) {
      h << "<td>" << r->robots << "</td><td class=\"l\" colspan=\"6\">could not run: " << html_escape(r->error) << "</td>";
    } else {
      const MissionScore& s = r->score;
      h << "<td>" << r->robots << "</td><td>" << format_fixed(s.time.strict, 3) << " / " << format_fixed(s.time.tolerant, 3) << "</td><td>"
        << format_fixed(s.radius.strict, 3) << " / " << format_fixed(s.radius.tolerant, 3) << "</td><td>" << format_fixed(s.joint.strict, 3) << " / "
        << format_fixed(s.joint.tolerant, 3) << "</td><td>" << s.overconfident_go_cells << "</td><td>" << (r->evaluable ? "yes" : "no")
        << "</td><td class=\"l\">" << (s.within(b, false) ? "within" : s.within(b, true) ? "within with 1 % shift" : "outside")
        << "</td>";
    }
    h << "<td class=\"l\">";
    if (has_page[static_cast<std::size_t>(r - results.data())]) h << "<a href=\"" << base << "page/index.html\">page</a> ";
    h << "<a href=\"" << base << "mission.yaml\">mission</a> <a href=\"" << base << "world.yaml\">world</a> ";
    if (r->generator_seed) h << "<a href=\"" << base << "plan.png\">plan</a> ";
    h << "<a href=\"" << base << "commands.txt\">commands</a></td></tr>\n";
  }
  h << "</table>\n</body></html>\n";
  if (!write_file(dir / "index.html", h.str())) problems.push_back("cannot write " + (dir / "index.html").string());
  return problems;
}

}  // namespace p3at::crosscheck
