// The true-pose error of a robot that turns around one way on some runs and
// the other way on others (docs/verifier.md, the error mixture): with a
// rotation-scale error the two groups end with heading errors of opposite
// sign, carried as lateral errors of opposite sign. `vipars verify`'s mean
// final distance against `vipars simulate`'s over 300 runs of the same
// mission in a world whose robot turns 1/0.98 of what odometry says (the
// models are vipars crosscheck's calibration of that robot). One Gaussian
// error, as before, put the robot 0.377 m from its goal on the U-turn (runs:
// 0.452) and 0.276 m on gen_1166 (runs: 0.469). About 3 s.
#include <doctest/doctest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

std::string vipars() { return p3at::test::vipars_binary(); }

std::string data(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/turn_error/" + name;
}

double predicted_distance(const std::string& mission) {
  const auto r = p3at::test::run_command(vipars() + " verify " + data(mission) + " --models " + data("models.yaml") + " --json");
  REQUIRE(!r.out.empty());
  const nlohmann::json j = nlohmann::json::parse(r.out);
  return j.at("robots").at(0).at("dist_mean_m").get<double>();
}

double simulated_distance(const std::string& mission, const std::string& world) {
  const auto r = p3at::test::run_command(vipars() + " simulate " + data(mission) + " --world " + data(world) +
                                         " --runs 300 --seed 1 --json");
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  double sum = 0.0;
  for (const nlohmann::json& run : j.at("runs")) sum += run.at("robots").at(0).at("dist_to_goal_m").get<double>();
  return sum / static_cast<double>(j.at("runs").size());
}

}  // namespace

TEST_CASE("a U-turn made either way: the predicted final distance is the runs' (two-sided heading error)") {
  const double predicted = predicted_distance("uturn.yaml");
  const double simulated = simulated_distance("uturn.yaml", "world.yaml");
  INFO("verify " << predicted << " m, 300 runs " << simulated << " m");
  CHECK(std::abs(predicted - simulated) < 0.03);
}

TEST_CASE("gen_1166: the U-turn's error carried through four more states") {
  const double predicted = predicted_distance("gen_1166.yaml");
  const double simulated = simulated_distance("gen_1166.yaml", "gen_1166_world.yaml");
  INFO("verify " << predicted << " m, 300 runs " << simulated << " m");
  CHECK(std::abs(predicted - simulated) < 0.04);
}

TEST_CASE("a U-turn decided by where the previous leg ended: both ways, as in the runs") {
  // The first leg's NOISE paths end heading a little left or right of north;
  // the second leg (no NOISE) turns around the shorter way from there. Started
  // from the first leg's mean pose every path turned the same way: the robot
  // was predicted on one side of its goal (mean x 4.19 m, sd 0.007 m) where
  // the runs end on both (mean x 4.52 m, sd 0.32 m).
  const auto r = p3at::test::run_command(vipars() + " verify " + data("uturn_after_leg.yaml") + " --models " +
                                         data("models.yaml") + " --json");
  REQUIRE(!r.out.empty());
  const nlohmann::json robot = nlohmann::json::parse(r.out).at("robots").at(0);
  const auto s = p3at::test::run_command(vipars() + " simulate " + data("uturn_after_leg.yaml") + " --world " +
                                         data("world_north.yaml") + " --runs 300 --seed 1 --json");
  REQUIRE(s.status == 0);
  double sum = 0.0, sum2 = 0.0;
  const nlohmann::json runs = nlohmann::json::parse(s.out).at("runs");
  for (const nlohmann::json& run : runs) {
    const double x = run.at("robots").at(0).at("true_x_m").get<double>();
    sum += x;
    sum2 += x * x;
  }
  const double n = static_cast<double>(runs.size());
  const double mean_x = sum / n, sd_x = std::sqrt(std::max(0.0, sum2 / n - mean_x * mean_x));
  const double predicted_x = robot.at("final_x_m").get<double>();
  // final_sd_m is sqrt(trace / 2) of the final position's covariance; the
  // spread is all across (x), so the x sd is final_sd_m * sqrt(2).
  const double predicted_sd_x = robot.at("final_sd_m").get<double>() * std::sqrt(2.0);
  INFO("verify x " << predicted_x << " sd " << predicted_sd_x << "; 300 runs x " << mean_x << " sd " << sd_x);
  CHECK(std::abs(predicted_x - mean_x) < 0.08);
  CHECK(predicted_sd_x > 0.7 * sd_x);
  CHECK(predicted_sd_x < 1.3 * sd_x);
}

namespace {

std::string turn_move(const std::string& name) {
  return std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/turn_move/" + name;
}

double verified_distance(const std::string& mission, const std::string& models) {
  const auto r = p3at::test::run_command(vipars() + " verify " + mission + " --models " + models + " --json");
  REQUIRE(!r.out.empty());
  return nlohmann::json::parse(r.out).at("robots").at(0).at("dist_mean_m").get<double>();
}

}  // namespace

TEST_CASE("a turn on wheels whose scales differ moves the robot forward: calibrated, and predicted") {
  // tests/unit/verifier/data/turn_move: left wheel 1.03, right 0.968. In a
  // turn the wheels' true speeds do not cancel: the centre moves (T/4)(1/r -
  // 1/l) per radian, T the nominal track 0.588 m: 9.14 mm/rad. Over the
  // mission's 110-degree turn, 1.7 cm along the heading that odometry never sees.
  const fs::path dir = p3at::test::scratch_dir("turn_move");
  const std::string models = (dir / "models.yaml").string();
  const auto cal = p3at::test::run_command(vipars() + " calibrate --world " + turn_move("world.yaml") +
                                           " --runs 20 --speed 0.3 --seed 3 --out " + models);
  REQUIRE(cal.status == 0);
  const YAML::Node node = YAML::LoadFile(models);
  const double k = node["robots"][0]["motion"]["trans_per_rad_m"].as<double>();
  const double expected = 2.0 / 0.0034 / 1000.0 / 4.0 * (1.0 / 0.968 - 1.0 / 1.03);
  CHECK(k == doctest::Approx(expected).epsilon(0.02));

  // The same models without it: what the verifier predicted before.
  std::string text;
  {
    std::ifstream in(models);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto at = text.find("trans_per_rad_m:");
  REQUIRE(at != std::string::npos);
  const std::string without = (dir / "models_without.yaml").string();
  {
    std::ofstream out(without);
    out << text.substr(0, at) << "trans_per_rad_m: 0" << text.substr(text.find('\n', at));
  }

  const std::string mission = turn_move("mission.yaml");
  const auto s = p3at::test::run_command(vipars() + " simulate " + mission + " --world " + turn_move("world.yaml") +
                                         " --runs 300 --seed 1 --json");
  REQUIRE(s.status == 0);
  const nlohmann::json runs = nlohmann::json::parse(s.out);
  double sum = 0.0;
  for (const nlohmann::json& run : runs.at("runs")) sum += run.at("robots").at(0).at("dist_to_goal_m").get<double>();
  const double simulated = sum / static_cast<double>(runs.at("runs").size());
  const double predicted = verified_distance(mission, models);
  const double before = verified_distance(mission, without);
  INFO("300 runs " << simulated << " m; verify " << predicted << " m, without the turn's motion " << before << " m");
  // The runs' final distance spreads by about 4 mm (sd); its mean is known to 0.3 mm.
  CHECK(std::abs(predicted - simulated) < 0.004);
  CHECK(std::abs(before - simulated) > 0.008);
  fs::remove_all(dir);
}
