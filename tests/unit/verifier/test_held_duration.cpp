// The duration of an exit under a NOISE held for the whole draw
// (engine/held_duration.hpp): 8 quadrature directions are samples of the
// crossing time T(phi) over the circle, and the duration is T's distribution
// with phi uniform. Checked against closed forms: T = 100 + 20 cos(phi)
// (arcsine law), a flat run of samples beside a rise (no dip below it), and
// directions still running at a redraw (the arc toward them spreads later).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/held_duration.hpp"

namespace {

using p3at::verifier::Mixture1;
using p3at::verifier::engine::FinishedPath;
using p3at::verifier::engine::held_duration;
using p3at::verifier::engine::HeldCircle;

constexpr double kPi = 3.14159265358979323846;
constexpr double kCycle = 0.1;

/// A path whose threshold crossing is at `t` cycles from the entry: it
/// fires at the check ceil(t), the crossing a fraction into that cycle.
FinishedPath crossing_at(double t, double weight) {
  FinishedPath p;
  p.walker.weight = weight;
  p.walker.cycles = static_cast<std::size_t>(std::ceil(t));
  p.crossing_c = t - (static_cast<double>(p.walker.cycles) - 1.0);
  p.crossing_sd = 0.0;
  return p;
}

/// P(the check that fires is at or before check n): the mass of the
/// components at those checks (each check is one component while the
/// mixture is not reduced, and each is a cycle wide).
double p_by_check(const Mixture1& m, double n) {
  double p = 0.0;
  for (const p3at::verifier::Component1& c : m.components) {
    CHECK(c.var == doctest::Approx(kCycle * kCycle / 12.0));
    if (c.mean < (n + 0.5) * kCycle) p += c.weight;
  }
  return p;
}

}  // namespace

TEST_CASE("a held NOISE's duration follows T(phi) over the circle: the arcsine law of a cosine") {
  // Directions off the symmetric layout, so no two samples are equal.
  std::vector<FinishedPath> paths;
  for (int j = 0; j < 8; ++j) {
    const double phi = 2.0 * kPi * (j + 0.3) / 8.0;
    paths.push_back(crossing_at(100.0 + 20.0 * std::cos(phi), 1.0 / 8.0));
  }
  HeldCircle circle;
  for (const FinishedPath& p : paths) circle.fired.push_back(&p);
  // Many components, so the reduction does not blur what is checked.
  const Mixture1 m = held_duration(circle, kCycle, 400);
  double worst = 0.0;
  for (int n = 75; n <= 125; ++n) {
    const double x = std::clamp((n - 100.0) / 20.0, -1.0, 1.0);
    const double exact = 1.0 - std::acos(x) / kPi;  // P(T <= n), T crossing, fired at ceil(T)
    worst = std::max(worst, std::abs(p_by_check(m, n) - exact));
  }
  CHECK(worst < 0.03);
  // The slowest sample is 100 + 20 cos(2 pi 0.3 / 8) = 118.9; the truth
  // reaches 120 and puts 1 - acos(0.945)/pi = 0.895 below 118.9, so mass
  // beyond the slowest sample must be there (the optimistic error at the top
  // is cutting it off).
  double slowest = 0.0;
  for (const FinishedPath& p : paths) slowest = std::max(slowest, static_cast<double>(p.walker.cycles));
  CHECK(1.0 - p_by_check(m, slowest - 1.0) > 0.05);
  CHECK(p_by_check(m, 120.0) == doctest::Approx(1.0));
  // Nothing before the truth's fastest check.
  CHECK(p_by_check(m, 79.0) < 1e-9);
}

TEST_CASE("a flat run of samples beside a rise stays flat: no dip below its time") {
  // Five directions cross at 100 cycles, three (toward a wall) at 130.
  std::vector<FinishedPath> paths;
  for (int j = 0; j < 8; ++j) paths.push_back(crossing_at(j < 5 ? 99.5 : 129.5, 1.0 / 8.0));
  HeldCircle circle;
  for (const FinishedPath& p : paths) circle.fired.push_back(&p);
  const Mixture1 m = held_duration(circle, kCycle, 400);
  CHECK(p_by_check(m, 99.0) < 1e-9);
  // The four arcs between the five flat directions fire at check 100 (4/8),
  // and the first few percent of the two arcs rising to 130 (zero slopes at
  // both ends: a smooth step) before the crossing passes 100.
  CHECK(p_by_check(m, 100.0) >= 0.5);
  CHECK(p_by_check(m, 100.0) < 0.53);
  CHECK(p_by_check(m, 129.0) < 0.875);
  CHECK(p_by_check(m, 130.0) == doctest::Approx(1.0));
}

TEST_CASE("toward a direction still running at the redraw, the arc fires later; toward another exit it does not") {
  // Directions 0-4 cross at 100, 90, 80, 90, 100 cycles; 5-7 did not fire
  // by the redraw at 110 (running) or fired another exit (not running).
  std::vector<FinishedPath> paths;
  for (const double t : {99.5, 89.5, 79.5, 89.5, 99.5}) paths.push_back(crossing_at(t, 1.0 / 8.0));
  HeldCircle circle;
  for (const FinishedPath& p : paths) circle.fired.push_back(&p);
  circle.fired.resize(8, nullptr);
  circle.draw_end_cycles = 110.0;

  circle.running.assign(8, false);
  const Mixture1 elsewhere = held_duration(circle, kCycle, 400);
  CHECK(p_by_check(elsewhere, 100.0) == doctest::Approx(1.0));
  CHECK(p_by_check(elsewhere, 79.0) < 1e-9);  // the turn at 80 is symmetric: no dip below it

  for (int j = 5; j < 8; ++j) circle.running[static_cast<std::size_t>(j)] = true;
  const Mixture1 running = held_duration(circle, kCycle, 400);
  // Directions 0 and 4's half arcs toward the running ones rise from 100
  // toward max(110, 100 + 10), half way there: 2/16 of the mass, 1/5 of the
  // fired 5/8, fires after check 100, and none after 106.
  const double later = 1.0 - p_by_check(running, 100.0);
  CHECK(later > 0.15);
  CHECK(later <= 0.2 + 1e-9);
  CHECK(p_by_check(running, 106.0) == doctest::Approx(1.0));
  CHECK(p_by_check(running, 79.0) < 1e-9);
}

TEST_CASE("the odometry's jitter spreads each crossing over its checks, the mass kept") {
  std::vector<FinishedPath> paths;
  for (int j = 0; j < 8; ++j) {
    FinishedPath p = crossing_at(50.25, 1.0);
    p.crossing_sd = 2.0;
    paths.push_back(p);
  }
  HeldCircle circle;
  for (const FinishedPath& p : paths) circle.fired.push_back(&p);
  const Mixture1 m = held_duration(circle, kCycle, 400);
  double total = 0.0, mean = 0.0;
  for (const auto& c : m.components) {
    total += c.weight;
    mean += c.weight * c.mean;
  }
  CHECK(total == doctest::Approx(1.0));
  // E[ceil(X)] for X ~ N(50.25, 4): about 50.25 + 0.5.
  CHECK(mean / kCycle == doctest::Approx(50.75).epsilon(0.002));
  CHECK(p_by_check(m, 50.0) == doctest::Approx(0.4503).epsilon(0.01));  // P(X <= 50) = Phi(-0.125)
}

namespace {

/// A circle of eight directions at phi_j = 2 pi (j + 0.3) / 8 with the arcs'
/// boundaries at the midpoints (what direction_arcs gives where nothing differs).
p3at::verifier::engine::ProbedCircle equal_arcs() {
  p3at::verifier::engine::ProbedCircle circle;
  for (int j = 0; j < 8; ++j) {
    circle.angles.push_back(2.0 * kPi * (j + 0.3) / 8.0);
    circle.boundaries.push_back(2.0 * kPi * (j + 0.8) / 8.0);
  }
  return circle;
}

p3at::verifier::engine::ProbeEnd probe_at(double angle, double t_cycles) {
  p3at::verifier::engine::ProbeEnd p;
  p.angle_rad = angle;
  if (t_cycles < 0.0) return p;  // still running at the redraw
  p.outcome = p3at::verifier::engine::draw_fired(0);
  p.cycles = static_cast<std::size_t>(std::ceil(t_cycles));
  p.crossing_c = t_cycles - (static_cast<double>(p.cycles) - 1.0);
  return p;
}

}  // namespace

TEST_CASE("a probed circle with equal arcs and no probes gives the equal spacing's duration") {
  // The arcs' code path on unequal spacing reduces to the equal spacing's
  // Hermite where the spacing is equal: the same components.
  std::vector<FinishedPath> paths;
  for (int j = 0; j < 8; ++j) paths.push_back(crossing_at(100.0 + 20.0 * std::cos(2.0 * kPi * (j + 0.3) / 8.0), 1.0 / 8.0));
  HeldCircle plain;
  for (const FinishedPath& p : paths) plain.fired.push_back(&p);
  plain.fired[6] = nullptr;  // one running neighbour, so the toward-the-redraw rule is compared too
  plain.running.assign(8, false);
  plain.running[6] = true;
  plain.draw_end_cycles = 125.0;
  HeldCircle probed = plain;
  const p3at::verifier::engine::ProbedCircle arcs = equal_arcs();
  probed.probed = &arcs;
  const Mixture1 a = held_duration(plain, kCycle, 400), b = held_duration(probed, kCycle, 400);
  REQUIRE(a.components.size() == b.components.size());
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    CHECK(b.components[i].mean == doctest::Approx(a.components[i].mean).epsilon(1e-12));
    CHECK(b.components[i].weight == doctest::Approx(a.components[i].weight).epsilon(1e-9));
  }
}

TEST_CASE("a fired direction's arc past the midpoint takes the times of the probes that fired in it") {
  // Direction 0 fires at 330 cycles, the other seven run past the redraw at
  // 480 (gen_7719's first leg: one direction through a corner's gap under a
  // NOISE held 48 s). Bisected toward each neighbour, the probes at half and
  // five eighths of the spacing fired too, at 336 and 340; those at three
  // quarters ran on: the arc reaches 11/16 of the spacing either side.
  const double spacing = 2.0 * kPi / 8.0;
  FinishedPath through = crossing_at(330.0, 1.0);
  HeldCircle circle;
  circle.fired.assign(8, nullptr);
  circle.fired[0] = &through;
  circle.running.assign(8, true);
  circle.running[0] = false;
  circle.draw_end_cycles = 480.0;
  p3at::verifier::engine::ProbedCircle arcs;
  for (int j = 0; j < 8; ++j) {
    arcs.angles.push_back(spacing * j);
    arcs.boundaries.push_back(spacing * (j + 0.5));
  }
  arcs.boundaries[0] = spacing * 11.0 / 16.0;
  arcs.boundaries[7] = 2.0 * kPi - spacing * 11.0 / 16.0;
  const p3at::verifier::engine::ProbedCircle arcs_alone = arcs;
  HeldCircle without_probes = circle;
  without_probes.probed = &arcs_alone;
  for (const double side : {1.0, -1.0}) {
    arcs.probes.push_back(probe_at(side * 0.5 * spacing, 336.0));
    arcs.probes.push_back(probe_at(side * 0.75 * spacing, -1.0));
    arcs.probes.push_back(probe_at(side * 0.625 * spacing, 340.0));
  }
  circle.probed = &arcs;
  const Mixture1 m = held_duration(circle, kCycle, 400);
  // Between the direction's 330 and the outer probes' 340; only the last
  // sixteenth of the spacing either side (1/11 of the arc), toward the
  // running probes, rises on toward the redraw, half way at most.
  CHECK(p_by_check(m, 329.0) < 1e-9);
  CHECK(p_by_check(m, 336.0) > 0.6);
  CHECK(p_by_check(m, 341.0) >= 10.0 / 11.0 - 1e-9);
  CHECK(p_by_check(m, 420.0) == doctest::Approx(1.0));
  // Without the probes the same arc rises toward the redraw: a third of
  // its mass after 360 cycles.
  const Mixture1 guessed = held_duration(without_probes, kCycle, 400);
  CHECK(1.0 - p_by_check(guessed, 360.0) > 0.3);
}
