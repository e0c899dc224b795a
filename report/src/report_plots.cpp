#include "p3at/report/report_plots.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

extern char** environ;

namespace p3at::vipars::report {
namespace {

// Colours: verification dark blue, validation orange (its band lighter); the
// regions as pale backgrounds, so the curves stay readable on top of them.
constexpr const char* kVerifyColour = "#1f4e9c";
constexpr const char* kValidateColour = "#d95f02";
constexpr const char* kBandColour = "#fdb863";
constexpr const char* kRegionColour[3] = {"#dddddd", "#fff4c2", "#d9f0d3"};
constexpr const char* kRegionLabel[3] = {"High confidence\n(unsuccessful)", "Uncertain",
                                         "High confidence\n(successful)"};
// One colour per slice (Figs. 12 and 13); slices beyond these reuse them.
constexpr const char* kSliceColours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#a6761d"};

std::string fixed(double value, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

/// A number short enough for a label: as few digits as it needs, up to 6 significant.
std::string shortest(double value) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  return buf;
}

std::string q(const std::string& text) { return gnuplot_quote(text); }

std::string terminal(bool png, int width, int height) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  return png ? "set terminal pngcairo" + size + " noenhanced font \"DejaVu Sans,11\"\n"
             : "set terminal svg" + size + " noenhanced font \"DejaVu Sans,11\" background \"white\"\n";
}

/// The whole script: settings once, then the plot commands for each terminal.
std::string script(const std::string& stem, const std::string& caption, const std::string& setup,
                   const std::string& plot, int width, int height) {
  std::string s = "# " + caption + "\n# Made by `vipars report`; redraw with `gnuplot " + stem +
                  ".gp` in this folder.\nset encoding utf8\n" + setup;
  for (const bool png : {true, false}) {
    s += terminal(png, width, height) + "set output " + q(stem + (png ? ".png" : ".svg")) + "\n" + plot;
  }
  return s + "unset output\n";
}

/// Background rectangles for the runs of consecutive axis points in the same
/// region (by the verification's curve), each from half-way to the previous
/// point to half-way to the next, labelled at the top when wide enough.
std::string region_bands(const std::vector<double>& x, const std::vector<double>& p, const Thresholds& t) {
  std::string s;
  const double span = x.back() - x.front();
  int tag = 1;
  for (std::size_t a = 0; a < x.size();) {
    const Region region = classify(p[a], t);
    std::size_t b = a;
    while (b + 1 < x.size() && classify(p[b + 1], t) == region) ++b;
    const double from = a == 0 ? x.front() : (x[a - 1] + x[a]) / 2;
    const double to = b + 1 == x.size() ? x.back() : (x[b] + x[b + 1]) / 2;
    const auto r = static_cast<std::size_t>(region);
    s += "set object " + std::to_string(tag) + " rectangle from " + exact(from) + ", graph 0 to " + exact(to) +
         ", graph 1 behind fillcolor rgb " + q(kRegionColour[r]) + " fillstyle solid 1.0 noborder\n";
    if (to - from >= 0.12 * span) {
      s += "set label " + std::to_string(tag) + " " + q(kRegionLabel[r]) + " at " + exact((from + to) / 2) +
           ", graph 0.93 center front\n";
    }
    ++tag;
    a = b + 1;
  }
  return s;
}

/// The max error of a curve: a black bar between the two values, labelled.
std::string mark_max(double x, const ErrorSummary& e, double axis_mid, const std::string& unit, int tag) {
  const bool right_half = x > axis_mid;
  return "set arrow " + std::to_string(tag) + " from " + exact(x) + ", " + exact(e.verify) + " to " + exact(x) + ", " +
         exact(e.validate) + " nohead front linecolor rgb \"black\" linewidth 3\n" + "set label " +
         std::to_string(tag) + " " +
         q("max |verify − validate| = " + fixed(e.max, 3) + "\nat " + shortest(x) + " " + unit) + " at " + exact(x) +
         ", " + exact((e.verify + e.validate) / 2) + (right_half ? " right offset -1,0" : " left offset 1,0") +
         " front\n";
}

std::string criterion_line(double x, const std::string& text) {
  return "set arrow 90 from " + exact(x) + ", graph 0 to " + exact(x) +
         ", graph 1 nohead back dashtype 2 linecolor rgb \"#555555\"\n" + "set label 90 " + q(text) + " at " +
         exact(x) + ", graph 0.02 left offset 0.5,0.6 textcolor rgb \"#555555\"\n";
}

std::string runs_text(const Side& w) { return w.runs ? std::to_string(*w.runs) + " runs" : std::string("runs"); }

struct CurveSpec {
  std::string stem, caption, title, xlabel, ylabel, unit, criterion_label;
  const std::vector<double>* axis;
  const std::vector<double>* verify;
  std::optional<double> max_at;
  double criterion;
};

FigureScript curve_figure(const PlotInputs& in, const CurveSpec& c, const ErrorSummary& e) {
  const std::vector<double>& x = *c.axis;
  std::string setup = "set title " + q(c.title) + "\nset xlabel " + q(c.xlabel) + "\nset ylabel " + q(c.ylabel) +
                      "\nset xrange [" + exact(x.front()) + ":" + exact(x.back()) + "]\nset yrange [-0.02:1.05]\n" +
                      "set grid front linecolor rgb \"#bbbbbb\"\nset key outside below center horizontal\nset bmargin "
                      "6\nset tics out\n" +
                      region_bands(x, *c.verify, in.thresholds);
  if (c.criterion >= x.front() && c.criterion <= x.back()) setup += criterion_line(c.criterion, c.criterion_label);
  if (c.max_at) setup += mark_max(*c.max_at, e, (x.front() + x.back()) / 2, c.unit, 91);
  const std::string file = q(c.stem + ".dat");
  const std::string plot = "plot " + file + " using 1:4:5 with filledcurves fillcolor rgb " + q(kBandColour) +
                           " fillstyle transparent solid 0.55 noborder title " + q("validation 95 % Wilson interval") +
                           ", \\\n     " + file + " using 1:3 with points pointtype 7 pointsize 0.7 linecolor rgb " +
                           q(kValidateColour) + " title " + q("validation (" + runs_text(in.validation) + ")") +
                           ", \\\n     " + file + " using 1:2 with lines linewidth 2.5 linecolor rgb " +
                           q(kVerifyColour) + " title " + q("verification (VIPARS)") + "\n";
  return {c.stem, c.caption, script(c.stem, c.caption, setup, plot, 1000, 620)};
}

FigureScript surfaces_figure(const PlotInputs& in) {
  const std::string stem = "fig11_joint";
  const std::string caption =
      "Fig. 11: P(t ≤ Tmax, every r ≤ Rmax) over the grid, verification (a) beside validation (b).";
  const std::string setup =
      "set xlabel \"Tmax (s)\" offset 0,-1\nset ylabel \"Rmax (m)\" offset 1,-1\nset zlabel \"P\" rotate parallel\n"
      "set zrange [0:1]\nset cbrange [0:1]\nset xyplane at 0\nset view 55, 300\nset grid\nset tics out\n"
      "set palette defined (0 \"#08306b\", 0.05 \"#2171b5\", 0.5 \"#f7f7f7\", 0.95 \"#cb181d\", 1 \"#67000d\")\n"
      "set pm3d depthorder\n";
  const std::string file = q(stem + ".dat");
  // Two panels side by side and one colour box right of both (it would overlap the right panel's axes).
  const std::string plot =
      "set multiplot title " + q(in.title + ": P(t ≤ Tmax, every r ≤ Rmax)") + "\n" +
      "set size 0.46, 0.92\nset origin 0, 0\nunset colorbox\nset title \"(a) verification (VIPARS)\"\nsplot " + file +
      " using 1:2:3 with pm3d notitle\n" +
      "set origin 0.46, 0\nset colorbox user origin 0.925, 0.25 size 0.015, 0.5\n" + "set title " +
      q("(b) validation (" + runs_text(in.validation) + ")") + "\nsplot " + file +
      " using 1:2:4 with pm3d notitle\nunset multiplot\n";
  return {stem, caption, script(stem, caption, setup, plot, 1400, 620)};
}

FigureScript slices_figure(const PlotInputs& in, bool over_tmax) {
  const Side& v = in.verification;
  const std::string stem = over_tmax ? "fig12_slices_tmax" : "fig13_slices_rmax";
  const std::vector<std::size_t>& idx = over_tmax ? in.slices.rmax : in.slices.tmax;
  const std::vector<double>& x = over_tmax ? v.tmax : v.rmax;
  const std::string caption =
      over_tmax ? "Fig. 12: P(t ≤ Tmax, every r ≤ Rmax) against Tmax at several Rmax (slices of Fig. 11)."
                : "Fig. 13: P(t ≤ Tmax, every r ≤ Rmax) against Rmax at several Tmax (slices of Fig. 11).";
  const std::string setup =
      "set title " +
      q(in.title + (over_tmax ? ": time criterion at several Rmax" : ": spatial criterion at several Tmax")) +
      "\nset xlabel " + q(over_tmax ? "Tmax (s)" : "Rmax (m)") + "\nset ylabel \"P(t ≤ Tmax, every r ≤ Rmax)\"\n" +
      "set xrange [" + exact(x.front()) + ":" + exact(x.back()) +
      "]\nset yrange [-0.02:1.05]\nset grid\nset tics out\n" + "set key outside right top box\n";
  const std::string file = q(stem + ".dat");
  std::string plot =
      "plot keyentry with lines linewidth 2.5 linecolor rgb \"black\" title \"verification\", \\\n"
      "     keyentry with points pointtype 7 linecolor rgb \"black\" title " +
      q("validation, 95 % band") + ", \\\n";
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const std::string colour = q(kSliceColours[k % std::size(kSliceColours)]);
    const std::string set = " index " + std::to_string(k);
    const std::string label =
        over_tmax ? "Rmax " + shortest(v.rmax[idx[k]]) + " m" : "Tmax " + shortest(v.tmax[idx[k]]) + " s";
    plot += "     " + file + set + " using 1:4:5 with filledcurves fillcolor rgb " + colour +
            " fillstyle transparent solid 0.15 noborder notitle, \\\n";
    plot += "     " + file + set + " using 1:3 with points pointtype 7 pointsize 0.5 linecolor rgb " + colour +
            " notitle, \\\n";
    plot += "     " + file + set + " using 1:2 with lines linewidth 2.5 linecolor rgb " + colour + " title " +
            q(label) + (k + 1 < idx.size() ? ", \\\n" : "\n");
  }
  if (idx.empty()) plot += "     NaN notitle\n";
  return {stem, caption, script(stem, caption, setup, plot, 1000, 620)};
}

FigureScript error_figure(const PlotInputs& in) {
  const std::string stem = "fig14_error";
  const ErrorSummary& e = in.comparison.joint;
  const std::string caption =
      "Fig. 14: the verification error |verify − validate| of P(t ≤ Tmax, every r ≤ Rmax) over the grid; "
      "the circle marks its maximum.";
  const double top = std::max(e.limit * 1.25, e.max);
  std::string setup =
      "set title " + q(in.title + ": |verification − validation| of P(t ≤ Tmax, every r ≤ Rmax)") +
      "\nset xlabel \"Tmax (s)\"\nset ylabel \"Rmax (m)\"\nset cblabel \"|verify − validate|\"\n" +
      "set autoscale xfix\nset autoscale yfix\nset tics out\nset cbrange [0:" + exact(top) + "]\n" +
      "set rmargin at screen 0.8\nset colorbox user origin screen 0.83, screen 0.15 size screen 0.02, screen 0.7\n" +
      "set cbtics add (" + q("limit " + shortest(e.limit)) + " " + exact(e.limit) + ")\n" +
      "set palette defined (0 \"white\", 0.3 \"#fee08b\", 0.65 \"#f46d43\", 1 \"#67001f\")\n";
  if (e.at_tmax_s && e.at_rmax_m) {
    setup += "set label 1 " +
             q("max " + fixed(e.max, 3) + " at " + shortest(*e.at_tmax_s) + " s, " + shortest(*e.at_rmax_m) + " m") +
             " at " + exact(*e.at_tmax_s) + ", " + exact(*e.at_rmax_m) +
             " point pointtype 6 pointsize 3 linecolor rgb \"black\" offset 1.5,1.5 front\n";
  }
  const std::string plot = "plot " + q(stem + ".dat") + " using 1:2:3 with image notitle\n";
  return {stem, caption, script(stem, caption, setup, plot, 1000, 680)};
}

}  // namespace

std::string gnuplot_quote(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::vector<FigureScript> figure_scripts(const PlotInputs& in) {
  const Side& v = in.verification;
  std::vector<FigureScript> out;
  out.push_back(curve_figure(
      in,
      {"fig09_time", "Fig. 9: P(t ≤ Tmax) against Tmax, verification against validation, with the three regions.",
       in.title + ": verification vs. validation of the time criterion", "Tmax (s)", "P(t ≤ Tmax)", "s",
       "criterion " + shortest(v.tmax_s) + " s", &v.tmax, &v.p_time_curve, in.comparison.time.at_tmax_s, v.tmax_s},
      in.comparison.time));
  out.push_back(
      curve_figure(in,
                   {"fig10_radius",
                    "Fig. 10: P(every r ≤ Rmax) against Rmax, verification against validation, with the three regions.",
                    in.title + ": verification vs. validation of the spatial criterion", "Rmax (m)",
                    "P(every robot's r ≤ Rmax)", "m", "criterion " + shortest(v.rmax_m) + " m", &v.rmax,
                    &v.p_radius_curve, in.comparison.radius.at_rmax_m, v.rmax_m},
                   in.comparison.radius));
  out.push_back(surfaces_figure(in));
  out.push_back(slices_figure(in, true));
  out.push_back(slices_figure(in, false));
  out.push_back(error_figure(in));
  return out;
}

Result<std::string> render(const std::string& gnuplot, const std::string& dir, const FigureScript& fig) {
  // gnuplot's output (warnings, errors) comes back through a pipe, so a
  // failure is reported with gnuplot's own words.
  int fds[2];
  if (::pipe(fds) != 0) return make_error(Error::Code::io, std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  std::string program = gnuplot, script_name = fig.stem + ".gp";
  char* argv[] = {program.data(), script_name.data(), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    return make_error(Error::Code::io, "cannot run '" + gnuplot + "': " + std::strerror(rc) +
                                           " (install gnuplot-nox, scripts/install-deps.sh, or pass --no-plots)");
  }
  std::string output;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n > 0) {
      output.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    // posix_spawnp cannot report a failed chdir or exec; the child exits 127 then.
    return make_error(Error::Code::io,
                      "'" + gnuplot + " " + script_name + "' in " + dir + " failed" +
                          (WIFEXITED(status) ? " (exit status " + std::to_string(WEXITSTATUS(status)) + ")"
                                             : std::string(" (killed by a signal)")) +
                          (output.empty() ? std::string() : ":\n" + output));
  }
  for (const char* ext : {".png", ".svg"}) {
    const std::string path = dir + "/" + fig.stem + ext;
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || st.st_size == 0) {
      return make_error(Error::Code::io, "gnuplot did not write " + path + (output.empty() ? "" : ":\n" + output));
    }
  }
  return output;
}

}  // namespace p3at::vipars::report
