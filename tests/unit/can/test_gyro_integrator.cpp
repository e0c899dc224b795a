#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "p3at/bridge/accessories/gyro_integrator.hpp"
#include "p3at/bridge/accessories/sequence_tracker.hpp"
#include "p3at/sim/rng.hpp"

using p3at::bridge::GyroIntegrator;
using p3at::bridge::SequenceTracker;

namespace {

constexpr std::int64_t kPeriodUs = 10'000;

// Feeds `seconds` of samples at 100 Hz with a standstill report every 100 ms.
std::int64_t feed(GyroIntegrator& g, std::int64_t t_us, double seconds, double rate_fn_offset, bool still,
                  p3at::sim::Rng* rng = nullptr, double noise = 0.0, double true_rate = 0.0) {
  const auto n = static_cast<int>(std::lround(seconds * 100));
  for (int i = 0; i < n; ++i) {
    t_us += kPeriodUs;
    const double measured = true_rate + rate_fn_offset + (rng != nullptr ? rng->gaussian(noise) : 0.0);
    g.add_sample(measured, 1, t_us);
    if (i % 10 == 9) g.set_standstill(still, t_us);
  }
  return t_us;
}

}  // namespace

TEST_CASE("sequence tracker accepts steps, rejects repeats and older counters, wraps") {
  SequenceTracker t;
  CHECK(t.accept(250) == 1);
  CHECK(t.accept(251) == 1);
  CHECK(t.accept(251) == 0);  // repeat
  CHECK(t.accept(249) == 0);  // behind
  CHECK(t.accept(254) == 3);  // two lost
  CHECK(t.accept(2) == 4);    // wrapped: 255, 0, 1 lost
  CHECK(t.accept(131) == 0);  // 129 ahead counts as behind
  CHECK(t.accept(129) == 127);
  t.reset();
  CHECK(t.accept(17) == 1);
}

TEST_CASE("the bias is learned while standing still and the heading does not drift") {
  GyroIntegrator g;
  p3at::sim::Rng rng(3);
  g.set_standstill(true, 0);
  const std::int64_t t = feed(g, 0, 3.0, 0.015, true, &rng, 0.005);
  CHECK(g.bias_valid());
  CHECK(g.bias_radps() == doctest::Approx(0.015).epsilon(0.05));
  // Standing still for 3 s with a 0.015 rad/s bias would drift 0.045 rad unaided.
  CHECK(std::fabs(g.heading_rad()) < 0.005);
  CHECK(g.learned_s() > 2.5);
  CHECK(t == 3'000'000);
}

TEST_CASE("turning integrates the bias-corrected rate") {
  GyroIntegrator g;
  g.set_standstill(true, 0);
  std::int64_t t = feed(g, 0, 2.0, 0.02, true);
  REQUIRE(g.bias_valid());
  const double before = g.heading_rad();
  g.set_standstill(false, t);
  t = feed(g, t, 2.0, 0.02, false, nullptr, 0.0, 0.5);  // true 0.5 rad/s for 2 s
  CHECK(g.heading_rad() - before == doctest::Approx(1.0).epsilon(0.002));
  CHECK(g.corrected_rate_radps() == doctest::Approx(0.5));
}

TEST_CASE("samples are not learned until a later report confirms standstill") {
  GyroIntegrator g;
  g.set_standstill(true, 0);
  // Samples arrive, but the robot starts moving before any later standstill report:
  for (int i = 1; i <= 50; ++i) g.add_sample(0.3, 1, i * kPeriodUs);
  g.set_standstill(false, 50 * kPeriodUs);
  CHECK(g.learned_s() == 0.0);
  CHECK(g.bias_radps() == 0.0);
  CHECK(g.heading_rad() == doctest::Approx(0.15));  // kept: the robot may have turned
}

TEST_CASE("a robot carried while its wheels stand still teaches nothing") {
  GyroIntegrator g;
  g.set_standstill(true, 0);
  std::int64_t t = feed(g, 0, 2.0, 0.01, true);
  const double bias = g.bias_radps();
  t = feed(g, t, 1.0, 0.01, true, nullptr, 0.0, 0.4);  // turned by hand: 0.4 rad/s
  CHECK(g.rejected_still_samples() > 50);
  CHECK(g.bias_radps() == doctest::Approx(bias));
  CHECK(t > 0);
}

TEST_CASE("lost samples are bridged, long gaps are not") {
  GyroIntegrator g;
  g.add_sample(1.0, 1, 10'000);
  g.add_sample(1.0, 5, 60'000);  // four lost: 50 ms at 1 rad/s
  CHECK(g.heading_rad() == doctest::Approx(0.06));
  g.add_sample(1.0, 200, 2'060'000);  // 2 s gap: only this sample's own period
  CHECK(g.heading_rad() == doctest::Approx(0.07));
  CHECK(g.unbridged_gaps() == 1);
  g.add_sample(std::nan(""), 1, 2'070'000);
  CHECK(g.heading_rad() == doctest::Approx(0.07));
  g.add_sample(1.0, 0, 2'080'000);
  CHECK(g.samples() == 3);
}

TEST_CASE("the bias follows a slow drift with its time constant") {
  p3at::bridge::GyroIntegratorConfig cfg;
  cfg.bias_time_constant_s = 5.0;
  GyroIntegrator g(cfg);
  g.set_standstill(true, 0);
  std::int64_t t = feed(g, 0, 2.0, 0.01, true);
  t = feed(g, t, 30.0, 0.03, true);  // the bias moved (temperature)
  CHECK(g.bias_radps() == doctest::Approx(0.03).epsilon(0.02));
}

TEST_CASE("standing still, the heading is held even while the bias estimate catches up") {
  GyroIntegrator g;  // 20 s bias time constant
  g.set_standstill(true, 0);
  std::int64_t t = feed(g, 0, 2.0, 0.01, true);
  const double before = g.heading_rad();
  // The bias moves to 0.03 rad/s; unaided, the lagging estimate would let ~0.15 rad drift in.
  t = feed(g, t, 10.0, 0.03, true);
  CHECK(std::fabs(g.heading_rad() - before) < 0.005);
  CHECK(g.bias_radps() > 0.015);
}
