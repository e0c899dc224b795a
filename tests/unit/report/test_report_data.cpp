// vipars report's data path, without gnuplot: reading the two documents,
// the data files' numbers against the JSON (exactly), the verification error
// against hand-computed answers, errors.json, and clear errors for documents
// that cannot be compared.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "p3at/report/report_dat.hpp"
#include "p3at/report/report_data.hpp"
#include "p3at/report/report_errors.hpp"
#include "report_test_docs.hpp"
#include "scratch.hpp"

namespace {

using namespace p3at::vipars::report;
using Json = nlohmann::json;

using p3at::test::scratch_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Side side(const Json& doc, const std::string& name) {
  auto s = side_from_json(doc, name);
  REQUIRE_MESSAGE(s.ok(), (s.ok() ? "" : s.error().message));
  return *s;
}

// A .dat file as gnuplot reads it: data sets (split by two blank lines),
// each a list of rows of numbers; comment lines skipped.
std::vector<std::vector<std::vector<double>>> read_dat(const std::string& path) {
  std::vector<std::vector<std::vector<double>>> sets(1);
  std::istringstream in(read_file(path));
  std::string line;
  int blanks = 0;
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (++blanks == 2 && !sets.back().empty()) sets.emplace_back();
      continue;
    }
    blanks = 0;
    if (line[0] == '#') continue;
    std::vector<double> row;
    std::istringstream fields(line);
    std::string field;
    while (fields >> field) row.push_back(std::strtod(field.c_str(), nullptr));
    sets.back().push_back(row);
  }
  if (sets.back().empty()) sets.pop_back();
  return sets;
}

double num(const Json& j) { return j.get<double>(); }

}  // namespace

TEST_CASE("the data files hold exactly the JSON's numbers") {
  const Json vj = p3at::test::verification_doc(), wj = p3at::test::validation_doc();
  const Side v = side(vj, "v.json"), w = side(wj, "w.json");
  REQUIRE(check_same_grid(v, w).ok());
  const Slices slices{{1, 0}, {2}};
  const std::string dir = scratch_dir("dat");
  REQUIRE(write_files(dir, figure_data(v, w, Thresholds{}, slices)).ok());
  const Json& vg = vj["grid"];
  const Json& wg = wj["grid"];

  SUBCASE("Fig. 9: the P(t) curves, the band, the error and the region per Tmax") {
    const auto sets = read_dat(dir + "/fig09_time.dat");
    REQUIRE(sets.size() == 1);
    REQUIRE(sets[0].size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
      const auto& row = sets[0][i];
      REQUIRE(row.size() == 7);
      CHECK(row[0] == num(vg["tmax"][i]));
      CHECK(row[1] == num(vg["p_time"][i]));
      CHECK(row[2] == num(wg["p_time"][i]));
      CHECK(row[3] == num(wg["p_time_ci_low"][i]));
      CHECK(row[4] == num(wg["p_time_ci_high"][i]));
      CHECK(row[5] == std::abs(num(vg["p_time"][i]) - num(wg["p_time"][i])));
    }
    // Regions by the verification's curve 0.0625, 0.5, 1 (bounds 0.05, 0.95).
    CHECK(sets[0][0][6] == 1);
    CHECK(sets[0][1][6] == 1);
    CHECK(sets[0][2][6] == 2);
  }
  SUBCASE("Fig. 10: the P(r) curves, including a value that is not 0.3") {
    const auto sets = read_dat(dir + "/fig10_radius.dat");
    REQUIRE(sets.size() == 1);
    REQUIRE(sets[0].size() == 2);
    CHECK(sets[0][1][1] == 0.30000000000000004);  // 17 digits: not rounded to 0.3
    CHECK(sets[0][1][1] != sets[0][1][2]);
    for (std::size_t j = 0; j < 2; ++j) {
      CHECK(sets[0][j][0] == num(vg["rmax"][j]));
      CHECK(sets[0][j][1] == num(vg["p_radius"][j]));
      CHECK(sets[0][j][2] == num(wg["p_radius"][j]));
      CHECK(sets[0][j][3] == num(wg["p_radius_ci_low"][j]));
      CHECK(sets[0][j][4] == num(wg["p_radius_ci_high"][j]));
    }
  }
  SUBCASE("Figs. 11 and 14: every cell, one block per Tmax") {
    const auto joint = read_dat(dir + "/fig11_joint.dat");
    const auto error = read_dat(dir + "/fig14_error.dat");
    REQUIRE(joint.size() == 1);  // blocks are split by one blank line, not two: one data set
    REQUIRE(joint[0].size() == 6);
    REQUIRE(error[0].size() == 6);
    std::size_t k = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < 2; ++j, ++k) {
        const auto& row = joint[0][k];
        CHECK(row[0] == num(vg["tmax"][i]));
        CHECK(row[1] == num(vg["rmax"][j]));
        CHECK(row[2] == num(vg["p_joint"][i][j]));
        CHECK(row[3] == num(wg["p_joint"][i][j]));
        CHECK(row[4] == num(wg["p_joint_ci_low"][i][j]));
        CHECK(row[5] == num(wg["p_joint_ci_high"][i][j]));
        CHECK(row[6] == std::abs(num(vg["p_joint"][i][j]) - num(wg["p_joint"][i][j])));
        CHECK(error[0][k] == std::vector<double>{row[0], row[1], row[6]});
      }
    }
    // One blank line after each Tmax block (gnuplot's grid format).
    const std::string text = read_file(dir + "/fig11_joint.dat");
    std::size_t blank_lines = 0;
    for (std::size_t p = text.find("\n\n"); p != std::string::npos; p = text.find("\n\n", p + 1)) ++blank_lines;
    CHECK(blank_lines == 3);
  }
  SUBCASE("Figs. 12 and 13: one data set per slice, in the order asked") {
    const auto by_tmax = read_dat(dir + "/fig12_slices_tmax.dat");
    REQUIRE(by_tmax.size() == 2);  // rmax indices 1 then 0
    for (std::size_t k = 0; k < 2; ++k) {
      const std::size_t j = slices.rmax[k];
      REQUIRE(by_tmax[k].size() == 3);
      for (std::size_t i = 0; i < 3; ++i) {
        CHECK(by_tmax[k][i] == std::vector<double>{num(vg["tmax"][i]), num(vg["p_joint"][i][j]),
                                                   num(wg["p_joint"][i][j]), num(wg["p_joint_ci_low"][i][j]),
                                                   num(wg["p_joint_ci_high"][i][j])});
      }
    }
    const auto by_rmax = read_dat(dir + "/fig13_slices_rmax.dat");
    REQUIRE(by_rmax.size() == 1);  // tmax index 2
    REQUIRE(by_rmax[0].size() == 2);
    for (std::size_t j = 0; j < 2; ++j) {
      CHECK(by_rmax[0][j] == std::vector<double>{num(vg["rmax"][j]), num(vg["p_joint"][2][j]), num(wg["p_joint"][2][j]),
                                                 num(wg["p_joint_ci_low"][2][j]), num(wg["p_joint_ci_high"][2][j])});
    }
    CHECK(read_file(dir + "/fig12_slices_tmax.dat").find("# rmax_m 1.5\n") != std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("the verification error: maxima, where, regions, intervals and the bounds") {
  const Side v = side(p3at::test::verification_doc(), "v.json");
  const Side w = side(p3at::test::validation_doc(), "w.json");
  const Comparison c = compare(v, w);

  CHECK(c.time.max == 0.125);
  CHECK(c.time.at_tmax_s == 20.0);
  CHECK_FALSE(c.time.at_rmax_m.has_value());
  CHECK(c.time.verify == 0.5);
  CHECK(c.time.validate == 0.375);
  CHECK(c.time.mean == doctest::Approx((0.0625 + 0.125) / 3));
  CHECK(c.time.within_ci == 2);  // 0.0625 is outside [0, 0.05]
  CHECK(c.time.points == 3);
  CHECK_FALSE(c.time.max_by_region[0].has_value());  // no Tmax where verify's P(t) < 0.05
  CHECK(c.time.max_by_region[1] == 0.125);
  CHECK(c.time.max_by_region[2] == 0.0);
  CHECK_FALSE(c.time.pass());

  CHECK(c.radius.max == std::abs(0.30000000000000004 - 0.3));
  CHECK(c.radius.max > 0.0);
  CHECK(c.radius.at_rmax_m == 1.5);
  CHECK(c.radius.within_ci == 2);
  CHECK(c.radius.pass());

  CHECK(c.joint.max == 0.09375);
  CHECK(c.joint.at_tmax_s == 30.0);
  CHECK(c.joint.at_rmax_m == 1.5);
  CHECK(c.joint.verify == 0.96875);
  CHECK(c.joint.validate == 0.875);
  CHECK(c.joint.points == 6);
  CHECK(c.joint.within_ci == 5);  // 0.96875 is outside [0.8, 0.95]
  CHECK(c.joint.max_by_region[0] == 0.0);
  CHECK(c.joint.max_by_region[1] == std::abs(0.05 - 0.0375));
  CHECK(c.joint.max_by_region[2] == 0.09375);
  CHECK_FALSE(c.joint.pass());
  CHECK_FALSE(c.pass());

  SUBCASE("looser bounds pass; the bound itself passes") {
    const Comparison loose = compare(v, w, Thresholds{}, Limits{0.125, 0.05, 0.09375});
    CHECK(loose.pass());
  }
  SUBCASE("other region bounds move the points between regions") {
    const Comparison other = compare(v, w, Thresholds{0.1, 0.5});
    CHECK(other.time.max_by_region[0] == 0.0625);  // 0.0625 < 0.1: unsuccessful
    CHECK(other.time.max_by_region[2] == 0.125);   // 0.5 >= 0.5: successful
  }
  SUBCASE("ties: the first maximum in axis order") {
    Json vj = p3at::test::verification_doc(), wj = p3at::test::validation_doc();
    vj["grid"]["p_time"] = {0.25, 0.5, 1};
    wj["grid"]["p_time"] = {0.5, 0.25, 1};
    const Comparison t = compare(side(vj, "v"), side(wj, "w"));
    CHECK(t.time.max == 0.25);
    CHECK(t.time.at_tmax_s == 10.0);
  }
  SUBCASE("identical documents: no error anywhere") {
    Json same = p3at::test::validation_doc();
    const Side a = side(same, "a");
    const Comparison z = compare(a, a);
    CHECK(z.time.max == 0.0);
    CHECK(z.radius.max == 0.0);
    CHECK(z.joint.max == 0.0);
    CHECK(z.joint.at_tmax_s == 10.0);  // the first point when every error is 0
    CHECK(z.pass());
  }
}

TEST_CASE("errors.json says what the comparison says") {
  const Side v = side(p3at::test::verification_doc(), "v.json");
  const Side w = side(p3at::test::validation_doc(), "w.json");
  const auto j = errors_json(compare(v, w), Thresholds{});
  CHECK(j["pass"] == false);
  CHECK(j["time"]["max_abs_error"] == 0.125);
  CHECK(j["time"]["at_tmax_s"] == 20.0);
  CHECK_FALSE(j["time"].contains("at_rmax_m"));
  CHECK(j["time"]["limit"] == 0.05);
  CHECK(j["time"]["pass"] == false);
  CHECK(j["time"]["max_abs_error_by_region"]["unsuccessful"].is_null());
  CHECK(j["radius"]["pass"] == true);
  CHECK(j["joint"]["max_abs_error"] == 0.09375);
  CHECK(j["joint"]["at_tmax_s"] == 30.0);
  CHECK(j["joint"]["at_rmax_m"] == 1.5);
  CHECK(j["joint"]["limit"] == 0.08);
  CHECK(j["joint"]["verify_within_validation_ci"] == 5);
  CHECK(j["region_low"] == 0.05);
}

TEST_CASE("documents that cannot be compared give clear errors") {
  SUBCASE("no grid") {
    Json vj = p3at::test::verification_doc();
    vj.erase("grid");
    auto s = side_from_json(vj, "v.json");
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().message.find("v.json: missing key 'grid'") == 0);
    CHECK(s.error().message.find("--tmax-range") != std::string::npos);
  }
  SUBCASE("a grid with one value on an axis") {
    Json vj = p3at::test::verification_doc();
    vj["grid"]["rmax"] = {1};
    auto s = side_from_json(vj, "v.json");
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().message.find("grid.rmax: expected at least 2 values") != std::string::npos);
  }
  SUBCASE("a row of the surface too short") {
    Json vj = p3at::test::verification_doc();
    vj["grid"]["p_joint"][1] = {0.05};
    auto s = side_from_json(vj, "v.json");
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().message == "v.json: grid.p_joint[1]: expected 2 numbers (one per rmax), got 1");
  }
  SUBCASE("a curve of the wrong length, a probability out of range, a string for a number") {
    Json a = p3at::test::verification_doc(), b = a, c = a;
    a["grid"]["p_time"] = {0.1, 0.2};
    b["grid"]["p_radius"][0] = 1.5;
    c["grid"]["tmax"][2] = "30";
    CHECK(side_from_json(a, "v").error().message == "v: grid.p_time: expected 3 values (one per axis value), got 2");
    CHECK(side_from_json(b, "v").error().message == "v: grid.p_radius[0]: expected a probability in [0, 1], got 1.5");
    CHECK(side_from_json(c, "v").error().message == "v: grid.tmax[2]: expected a number, got string");
  }
  SUBCASE("axes that differ") {
    Json wj = p3at::test::validation_doc();
    wj["grid"]["tmax"] = {10, 20, 31};
    const Side v = side(p3at::test::verification_doc(), "v.json"), w = side(wj, "w.json");
    const auto status = check_same_grid(v, w);
    REQUIRE_FALSE(status.ok());
    CHECK(status.error().message ==
          "the grids differ: tmax has 3 values 10..30 in v.json but 3 values 10..31 in w.json; run verify and "
          "validate with the same --tmax-range");
    Json fewer = p3at::test::validation_doc();
    fewer["grid"]["rmax"] = {1, 1.5, 2};
    fewer["grid"]["p_radius"] = {0.1, 0.3, 0.5};
    fewer["grid"]["p_radius_ci_low"] = {0, 0, 0};
    fewer["grid"]["p_radius_ci_high"] = {1, 1, 1};
    for (const char* key : {"p_joint", "p_joint_ci_low", "p_joint_ci_high"}) {
      for (auto& row : fewer["grid"][key]) row.push_back(0.5);
    }
    fewer["grid"].erase("region");
    const auto status2 = check_same_grid(v, side(fewer, "w3.json"));
    REQUIRE_FALSE(status2.ok());
    CHECK(status2.error().message.find("rmax has 2 values 1..1.5 in v.json but 3 values 1..2 in w3.json") !=
          std::string::npos);
  }
  SUBCASE("axis values within rounding are the same axis") {
    Json wj = p3at::test::validation_doc();
    wj["grid"]["rmax"] = {1.0000000000000002, 1.5};
    CHECK(check_same_grid(side(p3at::test::verification_doc(), "v"), side(wj, "w")).ok());
  }
  SUBCASE("the documents swapped") {
    const Side v = side(p3at::test::verification_doc(), "v.json"), w = side(p3at::test::validation_doc(), "w.json");
    CHECK(check_roles(v, w).ok());
    const auto swapped = check_roles(w, v);
    REQUIRE_FALSE(swapped.ok());
    CHECK(swapped.error().message.find("w.json: expected the output of `vipars verify --json`") == 0);
    const auto both_verify = check_roles(v, v);
    REQUIRE_FALSE(both_verify.ok());
    CHECK(both_verify.error().message.find("v.json: expected the output of `vipars validate --json`") == 0);
  }
  SUBCASE("a file that is not JSON: file:line:column") {
    const std::string dir = scratch_dir("bad");
    const std::string path = dir + "/bad.json";
    std::ofstream(path) << "{\n  \"mission\": \"toy\",\n  \"tmax_s\": 20,,\n}\n";
    auto s = load_side(path);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().message.find(path + ":3:16: expected JSON") == 0);
    auto missing = load_side(dir + "/none.json");
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().message == dir + "/none.json: cannot read");
    std::filesystem::remove_all(dir);
  }
}

TEST_CASE("slices: chosen where the curves rise, or at the values asked") {
  // The curve rises from index 2 (first >= 0.02) to index 7 (first where both >= 0.98).
  const std::vector<double> v{0, 0.01, 0.03, 0.2, 0.5, 0.8, 0.97, 0.99, 1, 1};
  const std::vector<double> w{0, 0, 0.02, 0.3, 0.6, 0.9, 0.99, 0.985, 1, 1};
  CHECK(default_slices(v, w, 4) == std::vector<std::size_t>{2, 4, 5, 7});
  CHECK(default_slices(v, w, 2) == std::vector<std::size_t>{2, 7});
  // Flat curves: spread over the whole axis.
  const std::vector<double> flat(10, 0.0);
  CHECK(default_slices(flat, flat, 4) == std::vector<std::size_t>{0, 3, 6, 9});

  const std::vector<double> axis{1, 1.5, 2, 2.5, 3};
  auto near = slices_at(axis, {2.1, 1, 2.9, 3}, "--rmax-slices");
  REQUIRE(near.ok());
  CHECK(*near == std::vector<std::size_t>{2, 0, 4});  // 2.9 and 3 are both the last value: once
  auto outside = slices_at(axis, {3.5}, "--rmax-slices");
  REQUIRE_FALSE(outside.ok());
  CHECK(outside.error().message == "--rmax-slices: 3.5 is outside the grid's axis 1..3");
}
