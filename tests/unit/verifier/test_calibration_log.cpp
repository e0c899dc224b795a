// The calibration log's CSV format (docs/calibration.md): what it reads, the
// exact round trip of what it writes, and each kind of error at its
// file:line:column.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "p3at/verifier/calibration.hpp"
#include "scratch.hpp"

namespace {

using p3at::verifier::CalibrationLog;
using p3at::verifier::CalibrationLogError;
using p3at::verifier::ManoeuvreKind;

constexpr std::string_view kHeader =
    "robot,id,kind,t_s,cmd_trans_mps,cmd_rot_radps,odom_x_m,odom_y_m,odom_theta_rad,true_x_m,true_y_m,true_theta_rad,"
    "sent_s,delivered_s,acked_s\n";

// A lab's log: two manoeuvres, true poses only at their ends, two messages.
const std::string kLog = std::string("# robot1, tape measure at each end\n") + std::string(kHeader) +
                         "robot1,0,straight,0,0.3,0,0,0,0,1.5,2,0.1,,,\n"
                         "robot1,0,straight,0.1,0.3,0,0.0165,0,0,,,,,,\n"
                         "\n"
                         "robot1,0,straight,0.2,0,0,0.05,0,0,1.6,2.01,0.1,,,\n"
                         "robot1, 1 ,spin,0.3,0,0.7,0.05,0,0,1.6,2.01,0.1,,,\r\n"
                         "robot1,1,spin,0.4,0,0,0.05,0,-3.1,1.6,2.01,-3.0,,,\n"
                         "robot1,0,message,,,,,,,,,,12.5,12.506,12.61\n"
                         "robot2,0,message,,,,,,,,,,+13,,\n";

std::string error_of(const std::string& text) {
  try {
    (void)p3at::verifier::parse_calibration_log(text, "log.csv");
    return "no error";
  } catch (const CalibrationLogError& e) {
    return e.what();
  }
}

// A log with `row` as its only data row (line 2).
std::string one_row(const std::string& row) { return std::string(kHeader) + row + "\n"; }

}  // namespace

TEST_CASE("a lab's log: manoeuvres with true poses at their ends, messages, comments, blank lines, CRLF") {
  const CalibrationLog log = p3at::verifier::parse_calibration_log(kLog, "lab.csv");
  REQUIRE(log.manoeuvres.size() == 2);
  const auto& straight = log.manoeuvres[0];
  CHECK(straight.robot == "robot1");
  CHECK(straight.id == 0);
  CHECK(straight.kind == ManoeuvreKind::straight);
  REQUIRE(straight.rows.size() == 3);
  CHECK(straight.rows[0].line == 3);
  CHECK(straight.rows[2].line == 6);
  CHECK(straight.rows[1].odom_x_m == 0.0165);
  CHECK(straight.rows[1].cmd_trans_mps == 0.3);
  CHECK_FALSE(straight.rows[1].truth.has_value());
  REQUIRE(straight.rows[2].truth.has_value());
  CHECK(straight.rows[2].truth->y_m == 2.01);
  const auto& spin = log.manoeuvres[1];
  CHECK(spin.kind == ManoeuvreKind::spin);
  CHECK(spin.id == 1);
  CHECK(spin.rows[0].cmd_rot_radps == 0.7);
  REQUIRE(log.messages.size() == 2);
  CHECK(log.messages[0].sender == "robot1");
  CHECK(log.messages[0].sent_s == 12.5);
  CHECK(log.messages[0].delivered_s == 12.506);
  CHECK(log.messages[0].acked_s == 12.61);
  CHECK(log.messages[1].sent_s == 13.0);
  CHECK_FALSE(log.messages[1].delivered_s.has_value());  // lost
  CHECK_FALSE(log.messages[1].acked_s.has_value());
}

TEST_CASE("columns in any order") {
  const std::string text =
      "id,robot,kind,true_theta_rad,true_y_m,true_x_m,t_s,odom_theta_rad,odom_y_m,odom_x_m,cmd_rot_radps,"
      "cmd_trans_mps,acked_s,delivered_s,sent_s\n"
      "4,r,spin,0.5,0.25,0.125,1,3,2,1,0.7,0,,,\n";
  const CalibrationLog log = p3at::verifier::parse_calibration_log(text, "x.csv");
  REQUIRE(log.manoeuvres.size() == 1);
  const auto& row = log.manoeuvres[0].rows[0];
  CHECK(log.manoeuvres[0].id == 4);
  CHECK(row.odom_x_m == 1.0);
  CHECK(row.odom_theta_rad == 3.0);
  CHECK(row.cmd_rot_radps == 0.7);
  CHECK(row.truth->x_m == 0.125);
  CHECK(row.truth->theta_rad == 0.5);
}

TEST_CASE("write then parse gives the same log, bit for bit") {
  CalibrationLog log = p3at::verifier::parse_calibration_log(kLog, "lab.csv");
  log.manoeuvres[0].rows[1].odom_y_m = 0.1 + 0.2;  // not a short decimal
  log.manoeuvres[1].rows[1].truth->theta_rad = -3.141592653589793;
  const std::string text = p3at::verifier::write_calibration_log(log);
  CalibrationLog again = p3at::verifier::parse_calibration_log(text, "again.csv");
  // Lines differ (the writer has no comments); everything else is identical.
  for (auto* l : {&log, &again}) {
    for (auto& m : l->manoeuvres) {
      for (auto& r : m.rows) r.line = 0;
    }
    for (auto& m : l->messages) m.line = 0;
  }
  CHECK(again == log);
  CHECK(p3at::verifier::write_calibration_log(again) == text);
}

TEST_CASE("errors name file:line:column and what was expected") {
  CHECK(error_of("") == "log.csv:1:1: empty calibration log (expected a header line: robot,id,kind,t_s,cmd_trans_mps,"
                        "cmd_rot_radps,odom_x_m,odom_y_m,odom_theta_rad,true_x_m,true_y_m,true_theta_rad,sent_s,"
                        "delivered_s,acked_s)");
  CHECK(error_of("robot,id,kind,t_s,cmd_trans_mps,cmd_rot_radps,odom_x_m,odom_y_m,odom_theta_rad,true_x_m,true_y_m,"
                 "true_theta_rad,sent_s,delivered_s,acked_z\n")
            .starts_with("log.csv:1:132: unknown column 'acked_z' in the header (expected the columns robot,id,"));
  CHECK(error_of("robot,id,kind,t_s,t_s\n") == "log.csv:1:19: duplicate column 't_s' in the header");
  CHECK(error_of("robot,id,kind,t_s,cmd_trans_mps,cmd_rot_radps,odom_x_m,odom_y_m,odom_theta_rad\n") ==
        "log.csv:1:1: missing column(s) in the header: true_x_m, true_y_m, true_theta_rad, sent_s, delivered_s, acked_s");

  CHECK(error_of(one_row("r1,0,straight,0,0.3,0,0,0,0,,,,,")) == "log.csv:2:33: expected 15 fields (as in the header), got 14");
  CHECK(error_of(one_row("r1,0,straight,0,0.3,0,0,0,0,,,,,,,")) == "log.csv:2:35: expected 15 fields (as in the header), got 16");
  CHECK(error_of(one_row("1r,0,straight,0,0.3,0,0,0,0,,,,,,")) ==
        "log.csv:2:1: invalid robot name '1r' (expected 1 to 64 letters, digits or '_', not starting with a digit)");
  CHECK(error_of(one_row("r1,-1,straight,0,0.3,0,0,0,0,,,,,,")) ==
        "log.csv:2:4: expected a whole number >= 0 for 'id', got '-1'");
  CHECK(error_of(one_row("r1,0,stright,0,0.3,0,0,0,0,,,,,,")) ==
        "log.csv:2:6: unknown kind 'stright' (expected straight, spin or message)");
  CHECK(error_of(one_row("r1,0,straight,0,fast,0,0,0,0,,,,,,")) ==
        "log.csv:2:17: expected a finite number for 'cmd_trans_mps', got 'fast'");
  CHECK(error_of(one_row("r1,0,straight,0,0.3,0,0,0,,,,,,,")) ==
        "log.csv:2:27: expected a finite number for 'odom_theta_rad', got an empty field");
  CHECK(error_of(one_row("r1,0,straight,0,0.3,0,0,0,nan,,,,,,")) ==
        "log.csv:2:27: expected a finite number for 'odom_theta_rad', got 'nan'");
  CHECK(error_of(one_row("r1,0,straight,0,0.3,0,0,0,0,1,2,,,,")) ==
        "log.csv:2:33: expected all three of true_x_m, true_y_m, true_theta_rad or none, got 'true_theta_rad' empty");
  CHECK(error_of(one_row("r1,0,straight,0,0.3,0,0,0,0,,,,5,,")) ==
        "log.csv:2:32: expected an empty 'sent_s' on a manoeuvre row, got '5'");
  CHECK(error_of(one_row("r1,0,message,1,,,,,,,,,5,,")) == "log.csv:2:14: expected an empty 't_s' on a message row, got '1'");
  CHECK(error_of(one_row("r1,0,message,,,,,,,,,,5,4.9,")) == "log.csv:2:25: delivered_s is before sent_s");
  CHECK(error_of(one_row("r1,0,message,,,,,,,,,,5,,4")) == "log.csv:2:26: acked_s is before sent_s");
  CHECK(error_of(one_row("r1,0,message,,,,,,,,,,,,")) ==
        "log.csv:2:23: expected a finite number for 'sent_s', got an empty field");
  CHECK(error_of(std::string(kHeader) + "r1,3,message,,,,,,,,,,5,,\nr1,3,message,,,,,,,,,,6,,\n") ==
        "log.csv:3:4: duplicate message 3 of r1 (first at line 2)");

  const std::string two = "r1,0,straight,0,0.3,0,0,0,0,,,,,,\n";
  CHECK(error_of(std::string(kHeader) + two + "r1,0,spin,0.1,0,0.5,0,0,0,,,,,,\n") ==
        "log.csv:3:6: manoeuvre 0 of r1 is a straight (line 2), this row says spin");
  CHECK(error_of(std::string(kHeader) + two + "r1,0,straight,0,0.3,0,0,0,0,,,,,,\n") ==
        "log.csv:3:15: t_s must increase within a manoeuvre (line 2 has 0.000000)");
  CHECK(error_of(std::string(kHeader) + two + "r1,1,spin,0.1,0,0.5,0,0,0,,,,,,\n" + "r1,0,straight,0.2,0,0,0,0,0,,,,,,\n") ==
        "log.csv:4:4: manoeuvre 0 of r1 (started at line 2) continues after another manoeuvre of r1 (a manoeuvre's "
        "rows must not be split)");
  // Another robot's rows in between are fine (two robots logged together).
  CHECK(error_of(std::string(kHeader) + two + "r2,0,spin,0.05,0,0.5,0,0,0,,,,,,\n" + "r1,0,straight,0.1,0,0,0,0,0,,,,,,\n") ==
        "no error");
  CHECK(error_of(std::string(kHeader) + std::string("r1,0,straight,0,0.3\0,0,0,0,0,,,,,,\n", 35)) ==
        "log.csv:2:1: unexpected NUL byte (not a text file?)");
}

TEST_CASE("files: a missing file, a directory, and a real one") {
  CHECK_THROWS_WITH(p3at::verifier::load_calibration_log("/nonexistent/log.csv"),
                    "/nonexistent/log.csv: cannot read calibration log: no such file");
  const std::filesystem::path dir = p3at::test::scratch_dir("calibration_log");
  CHECK_THROWS_WITH(p3at::verifier::load_calibration_log(dir.string()),
                    (dir.string() + ": cannot read calibration log: it is a directory").c_str());
  const std::string path = (dir / "lab.csv").string();
  {
    std::ofstream out(path, std::ios::binary);
    out << kLog;
  }
  CHECK(p3at::verifier::load_calibration_log(path) == p3at::verifier::parse_calibration_log(kLog, path));
  CHECK_THROWS_WITH_AS(p3at::verifier::load_calibration_log((dir / "nothing").string() + "/../lab.csv"),
                       doctest::Contains("cannot read calibration log"), std::runtime_error);
  std::filesystem::remove_all(dir);
}
