#include "p3at/report/report_html.hpp"

#include <sodium.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "p3at/common/number_format.hpp"

namespace p3at::vipars::report {
namespace {

std::string hex(const unsigned char* bytes, std::size_t n) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < n; ++i) {
    out += kDigits[bytes[i] >> 4];
    out += kDigits[bytes[i] & 0x0f];
  }
  return out;
}

bool sodium_ready() {
  static const bool ready = sodium_init() >= 0;  // 1 = already initialised: also fine
  return ready;
}

std::string verdict(bool pass) { return pass ? "<span class=pass>PASS</span>" : "<span class=fail>FAIL</span>"; }

std::string where(const ErrorSummary& e) {
  std::string s;
  if (e.at_tmax_s) s += "Tmax " + format_general(*e.at_tmax_s) + " s";
  if (e.at_rmax_m) s += std::string(s.empty() ? "" : ", ") + "Rmax " + format_general(*e.at_rmax_m) + " m";
  return s;
}

std::string region_cell(const std::optional<double>& value) { return value ? format_fixed(*value, 3) : "–"; }

std::string error_row(const std::string& name, const ErrorSummary& e) {
  return "<tr><td>" + html_escape(name) + "</td><td class=num>" + format_fixed(e.max, 4) + "</td><td>" + where(e) +
         "</td><td class=num>" + format_fixed(e.verify, 4) + " / " + format_fixed(e.validate, 4) + "</td><td class=num>≤ " +
         format_general(e.limit) + "</td><td>" + verdict(e.pass()) + "</td><td class=num>" + format_fixed(e.mean, 4) +
         "</td><td class=num>" + std::to_string(e.within_ci) + " / " + std::to_string(e.points) + "</td>" +
         "<td class=num>" + region_cell(e.max_by_region[0]) + "</td><td class=num>" + region_cell(e.max_by_region[1]) +
         "</td><td class=num>" + region_cell(e.max_by_region[2]) + "</td></tr>\n";
}

std::string point_row(const std::string& name, double v, double w, const Side& validation, std::size_t k) {
  std::string ci = "–";
  if (validation.point_ci_low && validation.point_ci_high) {
    ci = "[" + format_fixed((*validation.point_ci_low)[k], 3) + ", " + format_fixed((*validation.point_ci_high)[k], 3) + "]";
  }
  return "<tr><td>" + html_escape(name) + "</td><td class=num>" + format_fixed(v, 4) + "</td><td class=num>" + format_fixed(w, 4) +
         "</td><td class=num>" + ci + "</td><td class=num>" + format_fixed(std::abs(v - w), 4) + "</td></tr>\n";
}

std::string optional_cell(const std::optional<double>& x, int decimals) {
  return "<td class=num>" + (x ? format_fixed(*x, decimals) : std::string("–")) + "</td>";
}

/// Each robot's probability of ending within Rmax and its final distance to
/// its goal (mean, sd) on both sides, robots matched by name: which robot a
/// radius error comes from, and whether it is the distance's level or its
/// spread. Empty when either document has no robots.
std::string robot_table(const Side& v, const Side& w) {
  if (v.robots.empty() || w.robots.empty()) return "";
  std::string s = "<h2>Per robot: its final distance to its goal</h2>\n<table>\n<tr><th>robot</th><th>P(r ≤ Rmax) "
                  "verification</th><th>validation</th><th>mean distance (m) verification</th><th>validation</th>"
                  "<th>sd (m) verification</th><th>validation</th><th>sd ratio</th></tr>\n";
  for (const RobotSide& a : v.robots) {
    const auto b = std::find_if(w.robots.begin(), w.robots.end(), [&a](const RobotSide& x) { return x.name == a.name; });
    if (b == w.robots.end()) continue;
    std::optional<double> ratio;
    if (a.dist_sd_m && b->dist_sd_m && *b->dist_sd_m > 0.0) ratio = *a.dist_sd_m / *b->dist_sd_m;
    s += "<tr><td>" + html_escape(a.name) + "</td>" + optional_cell(a.p_radius, 4) + optional_cell(b->p_radius, 4) +
         optional_cell(a.dist_mean_m, 4) + optional_cell(b->dist_mean_m, 4) + optional_cell(a.dist_sd_m, 4) +
         optional_cell(b->dist_sd_m, 4) + optional_cell(ratio, 2) + "</tr>\n";
  }
  return s + "</table>\n<p>The validation's distances are over all its runs (a run that did not finish counts "
             "where its robot stood at the end).</p>\n";
}

std::string axis_text(const std::vector<double>& axis, const std::string& unit) {
  return format_general(axis.front()) + " .. " + format_general(axis.back()) + " " + unit + " (" + std::to_string(axis.size()) +
         " values)";
}

constexpr const char* kStyle =
    "body{font-family:'DejaVu Sans',sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}td,th{border:1px solid #ccc;padding:0.25em 0.6em;"
    "text-align:left}th{background:#f0f0f0}.num{text-align:right;font-variant-numeric:tabular-nums}"
    ".pass{color:#1a7f37;font-weight:bold}.fail{color:#c62828;font-weight:bold}"
    "pre{background:#f6f6f6;padding:0.6em;overflow-x:auto;white-space:pre-wrap}"
    "figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}figcaption{font-size:0.95em}"
    "code{font-size:0.95em}";

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string sha256_hex(std::string_view bytes) {
  unsigned char digest[crypto_hash_sha256_BYTES];
  (void)sodium_ready();
  crypto_hash_sha256(digest, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  return hex(digest, sizeof digest);
}

Result<std::string> sha256_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(Error::Code::not_found, path + ": cannot read");
  if (!sodium_ready()) return make_error(Error::Code::io, "libsodium failed to initialise");
  crypto_hash_sha256_state state;
  crypto_hash_sha256_init(&state);
  char buf[65536];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    crypto_hash_sha256_update(&state, reinterpret_cast<const unsigned char*>(buf),
                              static_cast<unsigned long long>(in.gcount()));
  }
  if (in.bad()) return make_error(Error::Code::io, path + ": read error");
  unsigned char digest[crypto_hash_sha256_BYTES];
  crypto_hash_sha256_final(&state, digest);
  return hex(digest, sizeof digest);
}

Result<InputFile> describe_input(const std::string& role, const std::string& path) {
  Result<std::string> hash = sha256_file(path);
  if (!hash) return hash.error();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  return InputFile{role, path, static_cast<std::uintmax_t>(in.tellg()), *hash};
}

std::string report_html(const HtmlInputs& in) {
  const Side& v = in.verification;
  const Side& w = in.validation;
  const Comparison& c = in.comparison;
  std::string s = "<!DOCTYPE html>\n<html lang=en>\n<head>\n<meta charset=utf-8>\n<title>" + html_escape(in.title) +
                  ": verification vs. validation</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  s += "<h1>" + html_escape(in.title) + ": verification vs. validation</h1>\n";
  s += "<p>Mission <b>" + html_escape(v.mission) + "</b>. " + verdict(c.pass()) +
       (c.pass() ? ": the verification stays within every bound on its error"
                 : ": the verification's error exceeds a bound (below)") +
       " (max |verify − validate| ≤ " + format_general(c.time.limit) + " over P(t ≤ Tmax), ≤ " + format_general(c.radius.limit) +
       " over P(every r ≤ Rmax), ≤ " + format_general(c.joint.limit) +
       " over the joint surface). Validation: " + (w.runs ? std::to_string(*w.runs) : std::string("?")) + " runs, " +
       (w.failed_runs ? std::to_string(*w.failed_runs) : std::string("?")) + " failed.</p>\n";

  s += "<h2>At the criterion point: Tmax " + format_general(v.tmax_s) + " s, Rmax " + format_general(v.rmax_m) + " m</h2>\n";
  s += "<table>\n<tr><th>probability</th><th>verification</th><th>validation</th><th>validation 95 % Wilson</th>"
       "<th>|difference|</th></tr>\n";
  s += point_row("P(t ≤ Tmax)", v.p_time, w.p_time, w, 0);
  s += point_row("P(every r ≤ Rmax)", v.p_radius, w.p_radius, w, 1);
  s += point_row("P(both) = P(success)", v.p_joint, w.p_joint, w, 2);
  s += "</table>\n<p>Threshold " + format_general(v.threshold) + "; the verification's decision: <b>" +
       html_escape(v.decision.value_or("?")) + "</b>; the validation's P(success) " +
       (w.p_joint >= w.threshold ? "meets" : "is below") + " its threshold " + format_general(w.threshold) + ".</p>\n";
  s += robot_table(v, w);

  s += "<h2>Verification error over the grid</h2>\n<p>Grid: Tmax " + axis_text(v.tmax, "s") + ", Rmax " +
       axis_text(v.rmax, "m") + ". Regions by the verification's probability: unsuccessful below " +
       format_general(in.thresholds.low) + ", successful at or above " + format_general(in.thresholds.high) +
       ", uncertain between. “Within CI”: points where the verification lies inside the validation's 95 % "
       "interval.</p>\n";
  s += "<table>\n<tr><th>over</th><th>max |error|</th><th>where</th><th>verify / validate there</th><th>bound</th>"
       "<th></th><th>mean |error|</th><th>within CI</th><th>max, unsuccessful</th><th>max, uncertain</th>"
       "<th>max, successful</th></tr>\n";
  s += error_row("P(t ≤ Tmax) curve", c.time);
  s += error_row("P(every r ≤ Rmax) curve", c.radius);
  s += error_row("joint surface", c.joint);
  s += "</table>\n<p>Machine-readable: <a href=errors.json>errors.json</a>.</p>\n";
  for (const std::string& note : in.notes) s += "<p>" + html_escape(note) + "</p>\n";

  s += "<h2>Figures</h2>\n";
  for (const FigureScript& f : in.figures) {
    const std::string stem = html_escape(f.stem);
    s += "<figure>\n";
    if (in.figures_rendered)
      s += "<a href=\"" + stem + ".svg\"><img src=\"" + stem + ".png\" alt=\"" + html_escape(f.caption) + "\"></a>\n";
    s += "<figcaption>" + html_escape(f.caption) + " " +
         (in.figures_rendered ? "<a href=\"" + stem + ".png\">PNG</a> · <a href=\"" + stem + ".svg\">SVG</a> · " : "") +
         "<a href=\"" + stem + ".dat\">data</a> · <a href=\"" + stem +
         ".gp\">gnuplot script</a></figcaption>\n</figure>\n";
  }
  if (!in.figures_rendered)
    s += "<p>Figures not rendered (--no-plots): run <code>gnuplot FILE.gp</code> in this folder.</p>\n";

  s += "<h2>Inputs</h2>\n<table>\n<tr><th>input</th><th>file</th><th>bytes</th><th>SHA-256</th></tr>\n";
  for (const InputFile& f : in.inputs) {
    s += "<tr><td>" + html_escape(f.role) + "</td><td><code>" + html_escape(f.path) + "</code></td><td class=num>" +
         std::to_string(f.bytes) + "</td><td><code>" + f.sha256 + "</code></td></tr>\n";
  }
  s += "</table>\n<h2>Commands</h2>\n";
  for (const auto& [what, command] : in.commands) {
    s += "<p>" + html_escape(what) + ":</p>\n<pre>" + html_escape(command) + "</pre>\n";
  }
  s += "</body>\n</html>\n";
  return s;
}

}  // namespace p3at::vipars::report
