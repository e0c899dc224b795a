// engine/trajectory_pace.hpp: the held NOISE paths of an interruptible leg
// read at the redrawn quadrature's pace (the time on the paths for each
// second of the state's time) and brought to its spread; LegTrajectory's
// path_time and redrawn_cov between and past the matched seconds.
#include <doctest/doctest.h>

#include <vector>

#include "engine/interruption.hpp"
#include "engine/trajectory_pace.hpp"

using namespace p3at::verifier::engine;

namespace {

/// One path along x at `speed` m/s for `cycles` cycles of 0.1 s.
LegTrajectory straight_path(double speed, std::size_t cycles) {
  LegTrajectory leg;
  leg.cycle_s = 0.1;
  leg.paths.emplace_back();
  for (std::size_t n = 0; n <= cycles; ++n) {
    TrajectoryPoint p;
    p.base.x_m = speed * 0.1 * static_cast<double>(n);
    leg.paths.back().push_back(p);
  }
  return leg;
}

/// A mean path along x at `speed` m/s, one sample per second for `seconds` s.
std::vector<PathSample> mean_path(double speed, int seconds) {
  std::vector<PathSample> out;
  for (int s = 0; s <= seconds; ++s) {
    PathSample p;
    p.offset_s = s;
    p.x_m = speed * s;
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST_CASE("a redrawn robot slower than the held paths reads them earlier") {
  // Held paths at 0.5 m/s, the redrawn mean at 0.4 m/s: at second s the
  // redrawn robot is where the paths were at 0.8 s.
  LegTrajectory leg = straight_path(0.5, 100);
  leg.path_time_s = path_times_at_pace(leg, mean_path(0.4, 6));
  REQUIRE(leg.path_time_s.size() == 7);
  for (std::size_t s = 0; s < leg.path_time_s.size(); ++s) {
    CHECK(leg.path_time_s[s] == doctest::Approx(0.8 * static_cast<double>(s)).epsilon(1e-9));
  }
  CHECK(leg.path_time(2.5) == doctest::Approx(2.0));
  CHECK(pose_at(leg, 0, 3.0).base.x_m == doctest::Approx(1.2));
  // Past the last matched second the paths go on at their own pace.
  CHECK(leg.path_time(8.0) == doctest::Approx(4.8 + 2.0));
  CHECK(pose_at(leg, 0, 8.0).base.x_m == doctest::Approx(0.5 * 6.8));
}

TEST_CASE("without a pace the paths keep their own time") {
  const LegTrajectory leg = straight_path(0.5, 50);
  CHECK(leg.path_time(3.3) == doctest::Approx(3.3));
  CHECK(pose_at(leg, 0, 3.3).base.x_m == doctest::Approx(1.65));
}

TEST_CASE("the matched time never goes back, and stops where the paths end") {
  // A redrawn mean that goes 1 m, then falls back (a mean pulled back by
  // walkers turning round) and then runs past where the paths end (2 m).
  LegTrajectory leg = straight_path(0.5, 40);
  std::vector<PathSample> redrawn = mean_path(0.5, 4);
  redrawn[3].x_m = 0.6;  // behind second 2's 1.0 m
  redrawn[4].x_m = 5.0;  // past the paths' end
  const std::vector<double> t = path_times_at_pace(leg, redrawn);
  REQUIRE(t.size() == 5);
  CHECK(t[2] == doctest::Approx(2.0));
  CHECK(t[3] == doctest::Approx(2.0));  // held, not back to 1.2 s
  CHECK(t[4] == doctest::Approx(4.0));  // the paths' last cycle
}

TEST_CASE("nothing to match: no pace") {
  const LegTrajectory leg = straight_path(0.5, 40);
  CHECK(path_times_at_pace(leg, {}).empty());
  CHECK(path_times_at_pace(LegTrajectory{}, mean_path(0.4, 5)).empty());
}

TEST_CASE("held offsets brought to the redrawn spread keep their shape and take its covariance") {
  // Four equally likely offsets on a cross, wide in x (0.4 m) and narrower
  // in y (0.2 m); the redrawn spread is 0.05 m by 0.08 m, turned 30 degrees.
  const std::vector<Eigen::Vector2d> held = {{0.4 * 1.41421356, 0.0}, {-0.4 * 1.41421356, 0.0},
                                             {0.0, 0.2 * 1.41421356}, {0.0, -0.2 * 1.41421356}};
  Eigen::Matrix2d held_cov = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& o : held) held_cov += 0.25 * o * o.transpose();
  const double c = 0.86602540378, s = 0.5;
  Eigen::Matrix2d turn;
  turn << c, -s, s, c;
  const Eigen::Matrix2d target = turn * Eigen::Vector2d(0.05 * 0.05, 0.08 * 0.08).asDiagonal() * turn.transpose();

  const std::vector<Eigen::Vector2d> out = offsets_at_spread(held, held_cov, target);
  REQUIRE(out.size() == held.size());
  Eigen::Matrix2d out_cov = Eigen::Matrix2d::Zero();
  Eigen::Vector2d out_mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& o : out) {
    out_cov += 0.25 * o * o.transpose();
    out_mean += 0.25 * o;
  }
  CHECK(out_mean.norm() < 1e-12);  // still around the same mean
  // The covariance is the target's, but for the 1 mm regularisation of the
  // held spread's inverse (a relative 1e-6 / 0.04 here).
  CHECK((out_cov - target).norm() < 1e-3 * target.norm());
  // Opposite offsets stay opposite: the same shape of points.
  CHECK((out[0] + out[1]).norm() < 1e-12);
  CHECK((out[2] + out[3]).norm() < 1e-12);
}

TEST_CASE("offsets that hardly spread are left alone, and the redrawn spreads are the mean path's variances") {
  const std::vector<Eigen::Vector2d> tiny = {{1e-4, 0.0}, {-1e-4, 0.0}};
  const Eigen::Matrix2d tiny_cov = Eigen::Vector2d(1e-8, 0.0).asDiagonal();
  const std::vector<Eigen::Vector2d> out = offsets_at_spread(tiny, tiny_cov, Eigen::Matrix2d::Identity() * 0.01);
  CHECK(out[0].x() == doctest::Approx(1e-4));

  std::vector<PathSample> mean = mean_path(0.4, 3);
  mean[2].var_xx = 0.04;
  mean[2].var_yy = 0.01;
  mean[2].var_xy = 0.005;
  const std::vector<Eigen::Matrix2d> spreads = redrawn_spreads(mean, 3);
  REQUIRE(spreads.size() == 3);
  CHECK(spreads[2](0, 0) == doctest::Approx(0.04));
  CHECK(spreads[2](0, 1) == doctest::Approx(0.005));
  CHECK(spreads[2](1, 0) == doctest::Approx(0.005));
  CHECK(spreads[2](1, 1) == doctest::Approx(0.01));
  LegTrajectory leg;
  leg.redrawn_cov_m2 = spreads;
  CHECK(leg.redrawn_cov(1.5)(0, 0) == doctest::Approx(0.02));  // halfway from 0 to 0.04
  CHECK(leg.redrawn_cov(9.0)(1, 1) == doctest::Approx(0.01));  // the last second's beyond it
}
