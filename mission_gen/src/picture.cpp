// A floor plan of a generated mission (gnuplot): walls in black, each robot's
// start (a triangle pointing where it faces) and route in its own colour,
// goals numbered in the order the robot visits them. For people checking
// that the generator writes missions a person could have written.

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "gen_internal.hpp"

namespace p3at::mission_gen {

std::string draw_picture(const GeneratedMission& g, const std::string& base, const std::string& gnuplot) {
  const std::string dat = base + ".dat";
  const std::string gp = base + ".gp";
  std::ostringstream d;
  d << "# walls: x1 y1 x2 y2\n";
  for (const sim::Segment& w : g.world.walls) d << w.a.x << ' ' << w.a.y << ' ' << w.b.x << ' ' << w.b.y << '\n';
  for (const RoutePlan& r : g.routes) {
    d << "\n\n# route of " << r.robot << ": x y step\n";
    for (std::size_t i = 0; i < r.points.size(); ++i) d << r.points[i].x_m << ' ' << r.points[i].y_m << ' ' << i << '\n';
  }
  d << "\n\n# starts: x y dx dy robot\n";
  for (const mission::RobotSpec& r : g.mission.robots) {
    const double th = r.start.theta_deg * std::numbers::pi / 180;
    d << r.start.x_m << ' ' << r.start.y_m << ' ' << 0.6 * std::cos(th) << ' ' << 0.6 * std::sin(th) << ' ' << r.name << '\n';
  }
  std::ofstream(dat) << d.str();
  const std::string leaf = dat.substr(dat.find_last_of('/') + 1);
  const std::string png = base.substr(base.find_last_of('/') + 1) + ".png";
  const std::size_t n = g.routes.size();
  std::ostringstream s;
  s << "# Floor plan of " << g.name << " (vipars generate --seed " << g.seed << "); gnuplot " << gp.substr(gp.find_last_of('/') + 1)
    << " redraws it.\nset terminal pngcairo size 1000,800 font ',10'\nset output '" << png << "'\n"
    << "set title '" << g.name << ": " << n << " robot" << (n == 1 ? "" : "s") << ", Tmax " << num(g.mission.criteria.tmax_s)
    << " s, Rmax " << num(g.mission.criteria.rmax_m) << " m' noenhanced\n"
    << "set size ratio -1\nset xlabel 'x (m)'\nset ylabel 'y (m)'\nset key outside right top noenhanced\nset grid\n"
    << "colors = \"#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e #17becf\"\n"
    << "plot '" << leaf << "' index 0 using 1:2:($3-$1):($4-$2) with vectors nohead lw 3 lc rgb 'black' title 'walls'";
  for (std::size_t i = 0; i < n; ++i) {
    s << ", \\\n  '' index " << i + 1 << " using 1:2 with linespoints lw 1.5 pt 7 ps 0.8 lc rgb word(colors," << i + 1
      << ") title '" << g.routes[i].robot << "'";
    s << ", \\\n  '' index " << i + 1 << " using 1:2:(sprintf('%d',$3)) every ::1 with labels offset 0.8,0.8 tc rgb word(colors,"
      << i + 1 << ") notitle";
  }
  s << ", \\\n  '' index " << n + 1 << " using 1:2:3:4 with vectors head filled lw 3 lc rgb 'black' notitle"
    << ", \\\n  '' index " << n + 1 << " using 1:2:5 with labels offset -1.5,-1 notitle\n";
  std::ofstream(gp) << s.str();
  if (gnuplot.empty()) return "";
  const std::string dir = base.find('/') == std::string::npos ? "." : base.substr(0, base.find_last_of('/'));
  const std::string cmd = "cd '" + dir + "' && " + gnuplot + " '" + gp.substr(gp.find_last_of('/') + 1) + "' 2>&1";
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof buf, p)) out += buf;
    const int status = pclose(p);
    if (status != 0) return out.empty() ? "gnuplot failed" : out;
  } else {
    return "cannot run gnuplot";
  }
  return "";
}

}  // namespace p3at::mission_gen
