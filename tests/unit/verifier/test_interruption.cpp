// A message interrupting a motion state (engine/interruption.hpp): the
// interruption time's bins against closed forms on a straight leg, and a
// robot recalled mid-leg ending where the recall found it.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/interruption.hpp"
#include "engine/race.hpp"
#include "outcome_mass.hpp"
#include "p3at/mission/loader.hpp"
#include "p3at/verifier/models.hpp"
#include "p3at/verifier/verify.hpp"

using namespace p3at;
using namespace p3at::verifier;
using namespace p3at::verifier::engine;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Paths moving along x at `speed` m/s from x = 0 (path j offset in y by j),
/// `cycles` cycles of 0.1 s.
LegTrajectory straight_leg(double speed, std::size_t cycles, std::size_t paths) {
  LegTrajectory leg;
  leg.cycle_s = 0.1;
  leg.paths.resize(paths);
  for (std::size_t j = 0; j < paths; ++j) {
    for (std::size_t n = 0; n <= cycles; ++n) {
      TrajectoryPoint p;
      p.base.x_m = speed * 0.1 * static_cast<double>(n);
      p.base.y_m = static_cast<double>(j);
      p.base.trans_mps = speed;
      leg.paths[j].push_back(p);
    }
  }
  return leg;
}

}  // namespace

TEST_CASE("truncated moments of a standard normal on (0, inf): the half-normal's") {
  double p = 0.0, mean = 0.0, var = 0.0;
  truncated_moments(Mixture1::gaussian(0.0, 1.0), 0.0, std::numeric_limits<double>::infinity(), p, mean, var);
  CHECK(p == doctest::Approx(0.5).epsilon(1e-9));
  CHECK(mean == doctest::Approx(std::sqrt(2.0 / kPi)).epsilon(1e-9));
  CHECK(var == doctest::Approx(1.0 - 2.0 / kPi).epsilon(1e-9));
  // A point mass counts where it lies.
  truncated_moments(Mixture1::point(3.0), 2.0, 3.0, p, mean, var);
  CHECK(p == 1.0);
  CHECK(mean == 3.0);
  CHECK(var == 0.0);
}

TEST_CASE("interruption on a straight leg: the bins' positions have the closed form's mean and variance") {
  // At constant speed v the position at tau ~ N(mu, s^2) is N(v mu, v^2 s^2):
  // the bins' mixture (positions at the bins' mean times plus the motion
  // within each bin) must have that mean and variance exactly.
  const double v = 0.3, mu = 30.0, s = 2.0;
  const LegTrajectory leg = straight_leg(v, 1000, 2);
  const std::vector<InterruptionBin> bins = interruption_bins(leg, Mixture1::gaussian(mu, s * s), 6);
  REQUIRE(bins.size() == 6);
  double mass = 0.0, mean = 0.0, second = 0.0;
  for (const InterruptionBin& b : bins) {
    CHECK(b.probability == doctest::Approx(1.0 / 6.0).epsilon(1e-6));
    mass += b.probability;
    mean += b.probability * b.base.x_m;
    second += b.probability * (b.base.x_m * b.base.x_m + b.within(0, 0));
    // The two paths are 1 m apart across the leg: offsets -0.5 and +0.5.
    REQUIRE(b.offsets.size() == 2);
    CHECK(b.offsets[0].y() == doctest::Approx(-0.5));
    CHECK(b.spread(1, 1) == doctest::Approx(0.25));
  }
  CHECK(mass == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(mean == doctest::Approx(v * mu).epsilon(1e-6));
  CHECK(second - mean * mean == doctest::Approx(v * v * s * s).epsilon(1e-4));
}

TEST_CASE("the robots that get through: every path that got through, the stuck ones weighted by the share freed") {
  // Four equally likely held paths, two of them pinned (stuck), the pinned
  // ones standing still at x = 0.
  LegTrajectory leg = straight_leg(0.2, 50, 4);
  leg.stuck = {0, 1, 0, 1};
  for (const std::size_t j : {1u, 3u}) {
    for (TrajectoryPoint& p : leg.paths[j]) p.base.x_m = 0.0;
  }
  // No redraw frees anyone: only the paths that got through (trajectory_subset's).
  auto none = trajectory_getting_through(leg, 0.0);
  REQUIRE(none);
  CHECK(none->paths.size() == 2);
  CHECK(none->weights == std::vector<double>{0.5, 0.5});
  // Half the pinned runs freed: a pinned path counts half as much as a free one.
  auto half = trajectory_getting_through(leg, 0.5);
  REQUIRE(half);
  REQUIRE(half->paths.size() == 4);
  CHECK(half->weight(0) == doctest::Approx(1.0 / 3.0));
  CHECK(half->weight(1) == doctest::Approx(1.0 / 6.0));
  CHECK(half->is_stuck(1));
  // Where a recall after 4 s finds such a robot: the mean of x over the weights.
  const auto bins = interruption_bins(*half, Mixture1::point(4.0), 1);
  REQUIRE(bins.size() == 1);
  CHECK(bins[0].base.x_m == doctest::Approx(0.8 * (2.0 / 3.0)));
  CHECK(bins[0].base.x_m < interruption_bins(*none, Mixture1::point(4.0), 1)[0].base.x_m);
  // All freed: every path as held. Out of range is clamped.
  CHECK(trajectory_getting_through(leg, 1.0)->weights == std::vector<double>{0.25, 0.25, 0.25, 0.25});
  CHECK(trajectory_getting_through(leg, 7.0)->weights == std::vector<double>{0.25, 0.25, 0.25, 0.25});
  // Nothing got through and nothing is freed: nothing.
  leg.stuck = {1, 1, 1, 1};
  CHECK_FALSE(trajectory_getting_through(leg, 0.0));
}

TEST_CASE("interruption after a path's end finds the robot where the path ended") {
  const LegTrajectory leg = straight_leg(0.3, 100, 1);  // 10 s, ends at x = 3 m
  const std::vector<InterruptionBin> bins = interruption_bins(leg, Mixture1::gaussian(50.0, 4.0), 6);
  REQUIRE(bins.size() == 1);  // it does not move over tau's spread: one bin
  CHECK(bins[0].base.x_m == doctest::Approx(3.0));
  CHECK(bins[0].within.norm() == doctest::Approx(0.0));
}

TEST_CASE("a robot recalled mid-leg ends where the recall found it, not at its leg's end") {
  const mission::Mission m =
      mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/recall.yaml");
  Models models;
  for (const mission::RobotSpec& r : m.robots) {
    RobotModel rm;
    rm.name = r.name;
    models.robots.push_back(rm);
  }
  models.comm.delivery_s = Mixture1::point(0.0);
  models.comm.ack_s = Mixture1::point(0.0);
  Result<SystemOutcome> o = evaluate_system(m, models);
  REQUIRE(o);
  CHECK(o->blocked_mass == 0.0);
  REQUIRE(o->branches.size() == 1);
  const RobotOutcome& r1 = o->branches[0].robots[0];
  const RobotOutcome& r2 = o->branches[0].robots[1];
  REQUIRE(r1.states.size() == 2);
  CHECK(r1.states[1] == "recalled");
  // The recall reaches robot1 one cycle after robot2 notifies (robot2's
  // finish is its acknowledgement, one cycle later still); by then robot1 has
  // driven at 0.3 m/s for all but its ramp-up (under a second, 0.3^2 / (2 x
  // 0.3 m/s^2) = 0.15 m behind 0.3 tau), and its final Stop then brakes it to
  // rest, as much again further (the default model's decel is 0.3 m/s^2 too):
  // it comes to rest near 0.3 tau (before the run-out was modelled its final
  // position was where the recall found it, 0.15 m short of that).
  const double tau = r2.finish_time_s.mean() - 0.1;
  CHECK(tau > 9.0);
  CHECK(r1.final_position.mean.x() < 0.3 * tau + 0.08);
  CHECK(r1.final_position.mean.x() > 0.3 * tau - 0.08);
  CHECK(r1.final_position.mean.y() == doctest::Approx(0.0).epsilon(1e-6));
  // It stops about when recalled, far from the end of the 20 m leg.
  CHECK(r1.finish_time_s.mean() == doctest::Approx(tau).epsilon(0.02));
}

namespace {

Models perfect(const mission::Mission& m) {
  Models models;
  for (const mission::RobotSpec& r : m.robots) {
    RobotModel rm;
    rm.name = r.name;
    models.robots.push_back(rm);
  }
  models.comm.delivery_s = Mixture1::gaussian(0.05, 0.0004);
  models.comm.ack_s = Mixture1::gaussian(0.1, 0.0004);
  return models;
}


}  // namespace

TEST_CASE("patrol until relieved: the laps' masses and the cut-off sum to 1; the patrol is left where the message finds it") {
  const mission::Mission m =
      mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/patrol.yaml");
  const Models models = perfect(m);
  Result<SystemOutcome> o = evaluate_system(m, models);
  REQUIRE(o);
  CHECK(test::accounted_mass(*o) == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(o->loop_cutoff_mass == 0.0);
  REQUIRE_FALSE(o->branches.empty());
  double relieved = 0.0;
  for (const Branch& b : o->branches) {
    const RobotOutcome& r1 = b.robots[0];
    REQUIRE_FALSE(r1.states.empty());
    CHECK(r1.states.back() == "relieved");
    // Several legs of the beat before the relief (robot2's leg is three beats long).
    CHECK(r1.states.size() >= 4);
    // On the beat, not at a leg's end by construction: anywhere from A to B.
    CHECK(r1.final_position.mean.x() > -0.3);
    CHECK(r1.final_position.mean.x() < 2.3);
    relieved += b.weight;
  }
  CHECK(relieved == doctest::Approx(1.0 - o->pruned_mass - o->blocked_mass).epsilon(1e-9));

  // A tighter budget cuts the loop off: every lap past it is mass reported
  // and counted as failure, never dropped.
  Models tight = models;
  tight.budget.max_events = 100;  // one entry per state: the second lap is cut
  Result<SystemOutcome> cut = evaluate_system(m, tight);
  REQUIRE(cut);
  CHECK(cut->loop_cutoff_mass > 0.5);
  CHECK(test::accounted_mass(*cut) == doctest::Approx(1.0).epsilon(1e-9));
  Result<VerifyResult> r = verify(m, tight, VerifyOptions{});
  REQUIRE(r);
  CHECK(r->p_joint <= 1.0 - cut->loop_cutoff_mass + 1e-12);
}

TEST_CASE("a patrol nobody relieves is cut off by the loop budget, quickly, and verify says so") {
  mission::Mission m =
      mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/tests/unit/verifier/data/patrol.yaml");
  // robot2 never notifies: it stops at its goal for good.
  m.robots[1].transitions.resize(1);
  m.robots[1].transitions[0].to = 2;
  for (mission::State& s : m.robots[1].states) s.outgoing.clear();
  m.robots[1].states[0].outgoing.push_back(0);
  const Models models = perfect(m);
  Result<SystemOutcome> o = evaluate_system(m, models);
  REQUIRE(o);
  CHECK(o->loop_cutoff_mass == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(o->branches.empty());
  Result<VerifyResult> r = verify(m, models, VerifyOptions{});
  REQUIRE(r);
  CHECK(r->p_joint == 0.0);
  CHECK(r->loop_cutoff_mass == doctest::Approx(1.0).epsilon(1e-9));
  CHECK_FALSE(r->go);
}

TEST_CASE("three or more independent times racing: the joint first-arrival probabilities, not pairwise products") {
  // Three equal normals: 1/3 each (the pairwise product gives 1/4 each,
  // summing to 3/4: the events X_c < X_o are correlated through X_c).
  const Mixture1 a = Mixture1::gaussian(10.0, 1.0);
  std::vector<double> p = first_probabilities({&a, &a, &a});
  REQUIRE(p.size() == 3);
  for (const double q : p) CHECK(q == doctest::Approx(1.0 / 3.0).epsilon(2e-3));

  // Different means against an independent numerical integral of
  // f_c(t) * prod_o (1 - F_o(t)) (Simpson, 20,000 intervals).
  const Mixture1 x0 = Mixture1::gaussian(10.0, 1.0), x1 = Mixture1::gaussian(10.5, 0.25), x2 = Mixture1::gaussian(11.0, 4.0);
  p = first_probabilities({&x0, &x1, &x2});
  const double means[3] = {10.0, 10.5, 11.0}, sds[3] = {1.0, 0.5, 2.0};
  for (int c = 0; c < 3; ++c) {
    const auto integrand = [&](double t) {
      double f = normal_pdf((t - means[c]) / sds[c]) / sds[c];
      for (int o = 0; o < 3; ++o) {
        if (o != c) f *= 1.0 - normal_cdf((t - means[o]) / sds[o]);
      }
      return f;
    };
    const int n = 20000;
    const double lo = -10.0, hi = 30.0, h = (hi - lo) / n;
    double sum = integrand(lo) + integrand(hi);
    for (int k = 1; k < n; ++k) sum += (k % 2 == 1 ? 4.0 : 2.0) * integrand(lo + k * h);
    CHECK(p[static_cast<std::size_t>(c)] == doctest::Approx(sum * h / 3.0).epsilon(3e-3));
  }

  // Equal point masses (three identical legs' quadrature nodes): a tie of the
  // quadrature, shared evenly once normalised (each gets (1/2)^2 of the cell).
  const Mixture1 s = Mixture1::point(5.0);
  p = first_probabilities({&s, &s, &s});
  CHECK(p[0] == doctest::Approx(0.25));
  CHECK(p[1] == doctest::Approx(0.25));
  CHECK(p[2] == doctest::Approx(0.25));
}
