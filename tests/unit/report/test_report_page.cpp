// vipars report's folder: what build_report writes (data, scripts, errors.json,
// index.html with the inputs' SHA-256 and the commands), the figures rendered
// by gnuplot (installed by scripts/install-deps.sh: this test needs it), and
// the command lines a page shows.

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "p3at/report/report_build.hpp"
#include "p3at/report/command_lines.hpp"
#include "p3at/report/report_html.hpp"
#include "p3at/report/report_plots.hpp"
#include "report_test_docs.hpp"
#include "scratch.hpp"

namespace {

using namespace p3at::vipars::report;
namespace fs = std::filesystem;

using p3at::test::scratch_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Side side(const nlohmann::json& doc, const std::string& name) {
  auto s = side_from_json(doc, name);
  REQUIRE(s.ok());
  return *s;
}

const char* const kStems[] = {"fig09_time",        "fig10_radius",      "fig11_joint",
                              "fig12_slices_tmax", "fig13_slices_rmax", "fig14_error"};

bool gnuplot_on_path() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && ::access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("SHA-256 of bytes and of a file (FIPS 180-2's 'abc')") {
  const std::string abc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
  CHECK(sha256_hex("abc") == abc);
  const std::string dir = scratch_dir("sha");
  std::ofstream(dir + "/abc.txt", std::ios::binary) << "abc";
  auto file = sha256_file(dir + "/abc.txt");
  REQUIRE(file.ok());
  CHECK(*file == abc);
  auto input = describe_input("test", dir + "/abc.txt");
  REQUIRE(input.ok());
  CHECK(input->bytes == 3);
  CHECK_FALSE(sha256_file(dir + "/missing").ok());
  fs::remove_all(dir);
}

TEST_CASE("build_report writes the data, scripts, errors.json and a page with hashes and commands") {
  const std::string dir = scratch_dir("build");
  const std::string vpath = dir + "/v.json", wpath = dir + "/w.json";
  std::ofstream(vpath) << p3at::test::verification_doc().dump(2);
  std::ofstream(wpath) << p3at::test::validation_doc().dump(2);
  const Side v = side(p3at::test::verification_doc(), vpath), w = side(p3at::test::validation_doc(), wpath);

  BuildOptions o;
  o.out_dir = dir + "/out";
  o.render = false;
  o.title = "Toy <mission> & co";
  o.input_files = {{"verification", vpath}, {"validation", wpath}};
  o.commands = {{"verification", "vipars verify m.yaml --models 'my models.yaml' --json > v.json"}};
  std::vector<std::string> lines;
  auto result = build_report(v, w, o, [&lines](const std::string& line) { lines.push_back(line); });
  REQUIRE_MESSAGE(result.ok(), (result.ok() ? "" : result.error().message));
  CHECK_FALSE(result->pass());
  CHECK(result->joint.max == 0.09375);
  CHECK_FALSE(lines.empty());

  for (const char* stem : kStems) {
    CHECK(fs::file_size(o.out_dir + "/" + stem + ".dat") > 0);
    const std::string script = read_file(o.out_dir + "/" + stem + ".gp");
    CHECK(script.find(std::string(stem) + ".dat") != std::string::npos);  // each plots its own data file
    CHECK(script.find("set output \"" + std::string(stem) + ".png\"") != std::string::npos);
    CHECK(script.find("set output \"" + std::string(stem) + ".svg\"") != std::string::npos);
    CHECK_FALSE(fs::exists(o.out_dir + "/" + stem + ".png"));  // not rendered
  }
  const auto errors = nlohmann::json::parse(read_file(o.out_dir + "/errors.json"));
  CHECK(errors == nlohmann::json::parse(errors_json(*result, o.thresholds).dump()));
  CHECK(errors["joint"]["max_abs_error"] == 0.09375);

  const std::string html = read_file(o.out_dir + "/index.html");
  CHECK(html.find(*sha256_file(vpath)) != std::string::npos);
  CHECK(html.find(*sha256_file(wpath)) != std::string::npos);
  CHECK(html.find("Toy &lt;mission&gt; &amp; co") != std::string::npos);  // escaped
  CHECK(html.find("<mission>") == std::string::npos);
  CHECK(html.find("--models &#39;my models.yaml&#39;") != std::string::npos);
  CHECK(html.find("0.1250") != std::string::npos);  // the P(t) curve's max error
  CHECK(html.find("0.0938") != std::string::npos);  // the surface's
  CHECK(html.find("Tmax 30 s, Rmax 1.5 m") != std::string::npos);
  CHECK(html.find("class=fail>FAIL") != std::string::npos);
  CHECK(html.find("64 runs, 2 failed") != std::string::npos);
  CHECK(html.find("gnuplot FILE.gp") != std::string::npos);  // no figures: says how to draw them
  fs::remove_all(dir);
}

TEST_CASE("the page compares each robot's final distance: level and spread, matched by name") {
  nlohmann::json vj = p3at::test::verification_doc(), wj = p3at::test::validation_doc();
  vj["robots"] = nlohmann::json::parse(R"([
    {"name": "robot1", "p_radius": 0.9, "dist_mean_m": 0.2280, "dist_sd_m": 0.0152},
    {"name": "robot2", "p_radius": 1.0, "dist_mean_m": 0.5}])");  // an older document: no dist_sd_m
  wj["robots"] = nlohmann::json::parse(R"([
    {"name": "robot2", "p_radius": 0.97, "dist_mean_m": 0.51, "dist_sd_m": 0.02},
    {"name": "robot1", "p_radius": 0.95, "dist_mean_m": 0.2283, "dist_sd_m": 0.0065}])");
  const std::string dir = scratch_dir("robots");
  BuildOptions o;
  o.out_dir = dir + "/out";
  o.render = false;
  o.title = "robots";
  REQUIRE(build_report(side(vj, "v.json"), side(wj, "w.json"), o).ok());
  const std::string html = read_file(o.out_dir + "/index.html");
  CHECK(html.find("<h2>Per robot: its final distance to its goal</h2>") != std::string::npos);
  // robot1's row: its own validation figures (not robot2's, listed first there) and the sd ratio.
  CHECK(html.find("<tr><td>robot1</td><td class=num>0.9000</td><td class=num>0.9500</td><td class=num>0.2280</td>"
                  "<td class=num>0.2283</td><td class=num>0.0152</td><td class=num>0.0065</td><td class=num>2.34</td></tr>") !=
        std::string::npos);
  CHECK(html.find("<tr><td>robot2</td><td class=num>1.0000</td><td class=num>0.9700</td><td class=num>0.5000</td>"
                  "<td class=num>0.5100</td><td class=num>–</td><td class=num>0.0200</td><td class=num>–</td></tr>") !=
        std::string::npos);
  // Documents without robots (as the toy ones): no table.
  REQUIRE(build_report(side(p3at::test::verification_doc(), "v.json"), side(p3at::test::validation_doc(), "w.json"), o).ok());
  CHECK(read_file(o.out_dir + "/index.html").find("Per robot") == std::string::npos);
  // A robot's figure that is not a number is an error naming it.
  vj["robots"][0]["dist_sd_m"] = "wide";
  const auto bad = side_from_json(vj, "v.json");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().message.find("v.json: robots[0].dist_sd_m: expected a number") == 0);
  fs::remove_all(dir);
}

TEST_CASE("build_report refuses before writing anything") {
  const std::string dir = scratch_dir("refuse");
  nlohmann::json wj = p3at::test::validation_doc();
  wj["grid"]["tmax"] = {10, 20, 40};
  BuildOptions o;
  o.out_dir = dir + "/out";
  o.render = false;
  auto mismatched = build_report(side(p3at::test::verification_doc(), "v"), side(wj, "w"), o);
  REQUIRE_FALSE(mismatched.ok());
  CHECK(mismatched.error().message.find("the grids differ: tmax") == 0);
  CHECK_FALSE(fs::exists(o.out_dir));

  o.input_files = {{"world", dir + "/no-such-world.yaml"}};
  auto unreadable = build_report(side(p3at::test::verification_doc(), "v"), side(p3at::test::validation_doc(), "w"), o);
  REQUIRE_FALSE(unreadable.ok());
  CHECK(unreadable.error().message == dir + "/no-such-world.yaml: cannot read");
  CHECK_FALSE(fs::exists(o.out_dir));

  o.input_files.clear();
  o.rmax_slices = {9};
  auto slice = build_report(side(p3at::test::verification_doc(), "v"), side(p3at::test::validation_doc(), "w"), o);
  REQUIRE_FALSE(slice.ok());
  CHECK(slice.error().message == "--rmax-slices: 9 is outside the grid's axis 1..1.5");
  fs::remove_all(dir);
}

TEST_CASE("gnuplot renders every figure as PNG and SVG") {
  REQUIRE_MESSAGE(gnuplot_on_path(), "gnuplot is not on PATH: scripts/install-deps.sh installs gnuplot-nox");
  const std::string dir = scratch_dir("render");
  BuildOptions o;
  o.out_dir = dir;
  const Side v = side(p3at::test::verification_doc(), "v"), w = side(p3at::test::validation_doc(), "w");
  auto result = build_report(v, w, o);
  REQUIRE_MESSAGE(result.ok(), (result.ok() ? "" : result.error().message));
  for (const char* stem : kStems) {
    const std::string png = read_file(dir + "/" + stem + ".png");
    const std::string svg = read_file(dir + "/" + stem + ".svg");
    CHECK_MESSAGE(png.size() > 1000, stem);
    CHECK(png.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
    CHECK(svg.find("<svg") != std::string::npos);
    CHECK(svg.find("</svg>") != std::string::npos);
  }
  const std::string html = read_file(dir + "/index.html");
  CHECK(html.find("<img src=\"fig09_time.png\"") != std::string::npos);
  CHECK(html.find("<a href=\"fig14_error.svg\">SVG</a>") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("a gnuplot that cannot run, or a script it rejects, is an error with gnuplot's words") {
  const std::string dir = scratch_dir("nognuplot");
  const FigureScript broken{"broken", "a broken figure", "plot 'no-such-file.dat' using 1:2\n"};
  std::ofstream(dir + "/broken.gp") << broken.text;
  auto missing = render(dir + "/no-such-gnuplot", dir, broken);
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().message.find("cannot run '" + dir + "/no-such-gnuplot'") == 0);
  if (gnuplot_on_path()) {
    auto rejected = render("gnuplot", dir, broken);
    REQUIRE_FALSE(rejected.ok());
    CHECK(rejected.error().message.find("no-such-file.dat") != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("command lines: quoting, ranges and commands rebuilt from the documents") {
  CHECK(shell_quote("examples/bo/mission.yaml") == "examples/bo/mission.yaml");
  CHECK(shell_quote("my file") == "'my file'");
  CHECK(shell_quote("it's") == "'it'\\''s'");
  CHECK(shell_quote("") == "''");
  CHECK(range_text({170, 171, 172}) == "170:172:1");
  CHECK(range_text({1, 1.05, 1.1, 1.15, 1.2}) == "1:1.2:0.05");
  CHECK_FALSE(range_text({1, 2, 4}).has_value());
  const Side w = side(p3at::test::validation_doc(), "w.json");
  CHECK(validate_command(w, "w.json") ==
        "vipars validate mission.yaml --world world.yaml --trials 64 --seed 7 --tmax 20 --rmax 1.5 "
        "--tmax-range 10:30:10 --rmax-range 1:1.5:0.5 --json > w.json");
  const Side v = side(p3at::test::verification_doc(), "v.json");
  CHECK(verify_command(v, "", "", "v.json") ==
        "vipars verify MISSION.yaml --models MODELS.yaml --tmax 20 --rmax 1.5 --tmax-range 10:30:10 "
        "--rmax-range 1:1.5:0.5 --json > v.json");
}
