// The redrawn NOISE's walker reduction (engine/noise_segments.hpp,
// reduce_walkers) on headings a whole turn apart. A robot turning about to a
// goal behind it turns left or right as the NOISE decides, and the two kinds
// of path then face the same way with headings about 2 pi apart as numbers
// (+3.0 and -3.3 rad). The reduction's restoring map gives the kept walkers
// the children's spread of pose and velocities: it must be the spread of
// the headings the robots face, not of the numbers (which would read the
// two turns as a heading spread of 3 rad). And a cluster that lies across the
// cut half a turn from the way the cloud faces is read whole, not as half a
// turn wide.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "engine/noise_segments.hpp"
#include "engine/path_stepper.hpp"

using namespace p3at::verifier::engine;

namespace {

constexpr double kTwoPi = 6.283185307179586;
using State5 = Eigen::Matrix<double, 5, 1>;
using Cov5 = Eigen::Matrix<double, 5, 5>;

/// 64 walkers of equal weight near (9.4, 2.4) facing about pi (toward -x),
/// in two groups 15 cm apart across the way: the left-turners' headings
/// about +3.0 rad, the right-turners' about -3.3 (the same way, a whole turn
/// apart as numbers), each with a small spread of place, heading, speed and
/// turn rate (low-discrepancy offsets, no two alike).
std::vector<Walker> turned_about() {
  std::vector<Walker> out;
  for (std::size_t i = 0; i < 64; ++i) {
    const double u = std::fmod(static_cast<double>(i) * 0.6180339887498949, 1.0) - 0.5;
    const double v = std::fmod(static_cast<double>(i) * 0.7548776662466927, 1.0) - 0.5;
    const bool left = i % 2 == 0;
    Walker w;
    w.q.x_m = 9.4 + 0.02 * u;
    w.q.y_m = (left ? 2.51 : 2.36) + 0.01 * v;
    w.q.theta_rad = 3.0 + (left ? 0.1 : -0.1) + 0.2 * u - (left ? 0.0 : kTwoPi);
    w.q.trans_mps = 0.1 + 0.01 * v;
    w.q.rot_radps = (left ? 0.1 : -0.1) + 0.05 * u;
    w.before = w.q;
    w.weight = 1.0 / 64.0;
    out.push_back(w);
  }
  return out;
}

/// Weighted mean and covariance of pose and velocities, each heading taken
/// as the way it faces: within half a turn of 3.0 rad.
void moments(const std::vector<Walker>& ws, State5& mean, Cov5& cov) {
  double total = 0.0;
  mean.setZero();
  std::vector<State5> states;
  for (const Walker& w : ws) {
    State5 s;
    s << w.q.x_m, w.q.y_m, 3.0 + std::remainder(w.q.theta_rad - 3.0, kTwoPi), w.q.trans_mps, w.q.rot_radps;
    states.push_back(s);
    mean += w.weight * s;
    total += w.weight;
  }
  mean /= total;
  cov.setZero();
  for (std::size_t k = 0; k < ws.size(); ++k) {
    const State5 d = states[k] - mean;
    cov += (ws[k].weight / total) * d * d.transpose();
  }
}

}  // namespace

TEST_CASE("reduce_walkers: the kept walkers have the children's spread of the headings they face") {
  const std::vector<Walker> children = turned_about();
  const std::vector<Walker> kept = reduce_walkers(children, 8);
  REQUIRE(kept.size() >= 2);
  REQUIRE(kept.size() <= 8);
  State5 mean_in, mean_out;
  Cov5 cov_in, cov_out;
  moments(children, mean_in, cov_in);
  moments(kept, mean_out, cov_out);
  for (int r = 0; r < 5; ++r) {
    CAPTURE(r);
    CHECK(mean_out(r) == doctest::Approx(mean_in(r)).epsilon(1e-9));
    for (int c = 0; c < 5; ++c) {
      CAPTURE(c);
      // The ridge the map adds (1e-9 of the trace) is the only slack.
      CHECK(std::abs(cov_out(r, c) - cov_in(r, c)) < 1e-8);
    }
  }
  // Every kept walker faces the way the children do (within half a
  // radian of 3.0 rad), never turned by the 2 pi between the numbers.
  for (const Walker& w : kept) CHECK(std::abs(std::remainder(w.q.theta_rad - 3.0, kTwoPi)) < 0.5);
}

TEST_CASE("reduce_walkers: a cluster lying across the half-turn cut is read whole, its members with it") {
  // Four tight groups of 16, each kept as one walker: facing 0, +1.5, pi and
  // -1.5 rad, 1 m apart. Their circular mean faces 0, so the cut lies at
  // +-pi, right across the third group, whose members' headings run from
  // pi - 0.05 to pi + 0.05 (continuous numbers, as a path's are). Read one
  // by one within half a turn of 0, that group would look a whole turn wide
  // and the map would swing every kept walker's heading by radians (a robot
  // pinned by a wall, turning on the spot, never looked still). Read through
  // its cluster's turn, only the groups' own 0.05 rad spread is restored.
  const double facings[4] = {0.0, 1.5, 3.141592653589793, -1.5};
  std::vector<Walker> children;
  for (std::size_t g = 0; g < 4; ++g) {
    for (std::size_t i = 0; i < 16; ++i) {
      const double u = std::fmod(static_cast<double>(i) * 0.6180339887498949, 1.0) - 0.5;
      Walker w;
      w.q.x_m = static_cast<double>(g) + 0.01 * u;
      w.q.y_m = 5.0 - 0.01 * u;
      w.q.theta_rad = facings[g] + 0.1 * u;
      w.q.trans_mps = 0.0;
      w.q.rot_radps = 0.2 * u;
      w.before = w.q;
      w.weight = 1.0 / 64.0;
      children.push_back(w);
    }
  }
  const std::vector<Walker> kept = reduce_walkers(children, 4);
  REQUIRE(kept.size() == 4);
  for (const Walker& w : kept) {
    // Which group it is: the one it stands by (1 m apart, 1 cm wide).
    const auto g = static_cast<std::size_t>(std::lround(w.q.x_m));
    REQUIRE(g < 4);
    CAPTURE(g);
    CHECK(std::abs(w.q.x_m - static_cast<double>(g)) < 0.05);
    CHECK(std::abs(w.q.theta_rad - facings[g]) < 0.2);
  }
}
