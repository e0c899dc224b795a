// drive_over_arcos(): the calibration manoeuvres through the ARCOS bridge.
// Ground truth, when the robot is p3at_sim, is read from the truth CSV that
// p3at_sim flushes every cycle: only at a manoeuvre's ends, when the robot
// stands still, so the two processes' clocks need not be matched.

#include "p3at/calibration_rig/calibrate_hal.hpp"

#include <charconv>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "p3at/bridge/arcos_client.hpp"
#include "p3at/hal/byte_stream.hpp"
#include "p3at/hal/clock.hpp"
#include "p3at/sim/truth_csv.hpp"

namespace p3at::vipars {
namespace {

// The columns read here: p3at_sim's own header (sim::truth_csv_header()) up to
// the true heading, so a file with more columns after them still reads.
std::string_view truth_header_start() {
  const std::string_view header = sim::truth_csv_header();
  return header.substr(0, header.find(",odom_x_m"));
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

bool parse(std::string_view text, double& value) {
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace

std::optional<verifier::TruePose> latest_truth(const std::string& truth_csv, const std::string& robot) {
  std::ifstream in(truth_csv);
  if (!in) throw std::runtime_error(truth_csv + ": cannot read the truth CSV");
  std::string line;
  if (!std::getline(in, line) || !std::string_view(line).starts_with(truth_header_start())) {
    throw std::runtime_error(truth_csv + ":1: not a p3at_sim truth CSV (expected a header starting " +
                             std::string(truth_header_start()) + ")");
  }
  std::optional<verifier::TruePose> latest;
  while (std::getline(in, line)) {
    // The last line may be half written while p3at_sim is running: a row
    // that does not parse is skipped, and a later read sees it whole.
    const std::vector<std::string_view> f = split(line);
    if (f.size() < 5 || f[1] != robot) continue;
    verifier::TruePose p;
    if (parse(f[2], p.x_m) && parse(f[3], p.y_m) && parse(f[4], p.theta_rad)) latest = p;
  }
  return latest;
}

void drive_over_arcos(const std::string& url, const std::string& robot, const ManoeuvrePlan& plan,
                      const std::string& truth_csv, std::vector<verifier::Manoeuvre>& out) {
  hal::SteadyClock clock;
  bridge::ClientConfig config;
  config.auto_reconnect = false;  // a calibration run that lost its robot is spoilt: report it
  config.log_name = "calibrate";
  bridge::ArcosClient client([url] { return hal::open_byte_stream(url); }, clock, config);
  if (const Status st = client.connect(); !st) {
    throw std::runtime_error("cannot connect to " + url + ": " + st.error().message);
  }
  if (!truth_csv.empty() && !latest_truth(truth_csv, robot)) {
    (void)client.disconnect();
    throw std::runtime_error(truth_csv + ": no rows for robot '" + robot +
                             "' (is --robots the name p3at_sim gives it?)");
  }
  const TruthProbe truth = [&](bool at_rest) -> std::optional<verifier::TruePose> {
    if (truth_csv.empty() || !at_rest) return std::nullopt;
    return latest_truth(truth_csv, robot);
  };
  std::int64_t next_id = 0;
  try {
    drive_manoeuvres(client, robot, plan, truth, next_id, out);
  } catch (...) {
    (void)client.disconnect();
    throw;
  }
  (void)client.disconnect();
}

}  // namespace p3at::vipars
