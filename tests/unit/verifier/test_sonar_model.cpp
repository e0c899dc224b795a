// The verifier's sonar model (engine/sonar_model.hpp) takes short cuts in its
// hot loop: segments out of the ring's reach are passed over, rays are cast
// only as far as AVOID_OBSTACLES can feel, and "is anything within reach"
// is answered from squared distances. Each short cut must give the answer
// the plain computation gives, which these tests hold it to on random rooms.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "engine/sonar_model.hpp"
#include "p3at/executive/behaviors.hpp"
#include "p3at/executive/sonar.hpp"

using namespace p3at::verifier::engine;
namespace exec = p3at::exec;

namespace {

constexpr double kMaxRangeM = 5.0;

/// A room of 16 x 12 m with a few long walls and many small pillars.
std::vector<Segment> random_room(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(0.0, 16.0), y(0.0, 12.0), side(0.2, 3.0), unit(0.0, 1.0);
  std::vector<Segment> walls{{0, 0, 16, 0}, {16, 0, 16, 12}, {16, 12, 0, 12}, {0, 12, 0, 0}};
  for (int i = 0; i < 30; ++i) {
    const double x0 = x(rng), y0 = y(rng), a = unit(rng) * 6.283185307179586, l = side(rng);
    walls.push_back({x0, y0, x0 + l * std::cos(a), y0 + l * std::sin(a)});
  }
  return walls;
}

/// The distance along a unit ray to the nearest segment it crosses, by
/// Cramer's rule in long double: an independent reference, not the model's
/// own arithmetic, so agreement to 1e-9 m says no segment was wrongly skipped.
long double wide(double v) { return static_cast<long double>(v); }

double reference_range(const std::vector<Segment>& segments, long double ox, long double oy, long double cx,
                       long double cy, double max_range_m) {
  long double best = wide(max_range_m);
  for (const Segment& s : segments) {
    const long double ex = wide(s.x1) - wide(s.x0), ey = wide(s.y1) - wide(s.y0);
    const long double det = cx * ey - cy * ex;
    if (std::fabs(det) < 1e-12L) continue;
    const long double wx = wide(s.x0) - ox, wy = wide(s.y0) - oy;
    const long double t = (wx * ey - wy * ex) / det, u = (wx * cy - wy * cx) / det;
    if (t >= 0 && u >= 0 && u <= 1 && t < best) best = t;
  }
  return static_cast<double>(best);
}

std::array<double, exec::kP3atSonarCount> reference_ranges(const std::vector<Segment>& segments, double x, double y,
                                                           double theta) {
  std::array<double, exec::kP3atSonarCount> out{};
  const long double c = std::cos(wide(theta)), s = std::sin(wide(theta));
  for (std::size_t i = 0; i < exec::kP3atSonarCount; ++i) {
    const exec::SonarPose& sonar = exec::kP3atSonars[i];
    const long double h = wide(sonar.heading_deg) * 3.14159265358979323846L / 180.0L + wide(theta);
    const long double sx = wide(sonar.x_m), sy = wide(sonar.y_m);
    const long double ox = wide(x) + c * sx - s * sy, oy = wide(y) + s * sx + c * sy;
    out[i] = reference_range(segments, ox, oy, std::cos(h), std::sin(h), kMaxRangeM);
  }
  return out;
}

}  // namespace

TEST_CASE("every sonar reads the nearest wall its ray crosses, however many walls are out of reach") {
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> x(0.5, 15.5), y(0.5, 11.5), theta(-3.2, 3.2);
  int hits = 0, misses = 0;
  for (int room = 0; room < 40; ++room) {
    const std::vector<Segment> walls = random_room(rng);
    for (int pose = 0; pose < 50; ++pose) {
      const double px = x(rng), py = y(rng), pth = theta(rng);
      const auto got = sonar_ranges(walls, px, py, pth, kMaxRangeM);
      const auto want = reference_ranges(walls, px, py, pth);
      for (std::size_t i = 0; i < got.size(); ++i) {
        REQUIRE(got[i] == doctest::Approx(want[i]).epsilon(1e-9));
        (got[i] < kMaxRangeM ? hits : misses) += 1;
      }
    }
  }
  // Both kinds of reading were exercised, so the cull was tested both ways.
  CHECK(hits > 5000);
  CHECK(misses > 1000);
}

TEST_CASE("a shortened cast keeps every reading within it to the bit and reads 'nothing' beyond") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(0.5, 15.5), y(0.5, 11.5), theta(-3.2, 3.2), cast(0.5, 4.5);
  int kept = 0, dropped = 0;
  for (int room = 0; room < 40; ++room) {
    const std::vector<Segment> walls = random_room(rng);
    for (int pose = 0; pose < 50; ++pose) {
      const double px = x(rng), py = y(rng), pth = theta(rng), cast_m = cast(rng);
      const auto full = sonar_ranges(walls, px, py, pth, kMaxRangeM);
      const auto cut = sonar_ranges(walls, px, py, pth, kMaxRangeM, cast_m);
      for (std::size_t i = 0; i < full.size(); ++i) {
        if (full[i] < cast_m) {
          REQUIRE(cut[i] == full[i]);
          ++kept;
        } else {
          REQUIRE(cut[i] == kMaxRangeM);
          if (full[i] < kMaxRangeM) ++dropped;
        }
      }
    }
  }
  CHECK(kept > 3000);
  CHECK(dropped > 3000);
}

TEST_CASE("readings beyond the path stepper's cast do not change GoToGuarded's command by a bit") {
  // path_stepper.cpp casts to contact distance + sphere + 0.35 m + 0.5 m: a
  // reading farther than that puts its point outside AVOID_OBSTACLES' sphere,
  // so the command from the shortened readings must equal the full one.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(0.5, 15.5), y(0.5, 11.5), theta(-3.2, 3.2), sphere(0.1, 2.0),
      noise(-3.2, 3.2);
  exec::BehaviorConfig config;
  config.max_speed_mps = 0.4;
  int differing_readings = 0;
  for (int room = 0; room < 20; ++room) {
    const std::vector<Segment> walls = random_room(rng);
    for (int pose = 0; pose < 50; ++pose) {
      p3at::mission::GoToGuardedParams params;
      params.goal = {x(rng), y(rng)};
      params.sphere_m = sphere(rng);
      params.avoid_gain = 1.5;
      params.noise_gain = 0.2;
      const double cast_m = config.robot_radius_m + params.safety_margin_m + params.sphere_m + 0.35 + 0.5;
      // The sonar sees from the true pose; the command is for the odometric
      // one, a few centimetres and a degree off.
      const double px = x(rng), py = y(rng), pth = theta(rng);
      const exec::Pose<double> believed{px - 0.03, py + 0.02, pth + 0.017};
      const auto full = sonar_ranges(walls, px, py, pth, kMaxRangeM);
      const auto cut = sonar_ranges(walls, px, py, pth, kMaxRangeM, cast_m);
      differing_readings += static_cast<int>(full != cut);
      const auto points_full = exec::sonar_obstacles(std::span<const double, exec::kP3atSonarCount>(full), believed);
      const auto points_cut = exec::sonar_obstacles(std::span<const double, exec::kP3atSonarCount>(cut), believed);
      const double a = noise(rng);
      const exec::Vec2<double> direction{std::cos(a), std::sin(a)};
      const auto v_full = exec::go_to_guarded(params, believed, points_full.view(), direction, config);
      const auto v_cut = exec::go_to_guarded(params, believed, points_cut.view(), direction, config);
      REQUIRE(v_full.trans_mps == v_cut.trans_mps);
      REQUIRE(v_full.rot_radps == v_cut.rot_radps);
    }
  }
  CHECK(differing_readings > 500);  // the shortened cast did drop readings
}

TEST_CASE("'is any wall within reach' answers as the exact distance does, even at the edge of reach") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(-1.0, 17.0), y(-1.0, 13.0), reach(0.05, 3.0);
  int inside = 0, outside = 0;
  for (int room = 0; room < 20; ++room) {
    const std::vector<Segment> walls = random_room(rng);
    for (int point = 0; point < 200; ++point) {
      const double px = x(rng), py = y(rng);
      const double nearest = nearest_distance(walls, px, py);
      // A random reach, and reaches a hair either side of the nearest wall.
      for (const double r : {reach(rng), nearest, std::nextafter(nearest, 0.0),
                             std::nextafter(nearest, std::numeric_limits<double>::infinity())}) {
        const bool want = nearest <= r;
        REQUIRE(any_within(walls, px, py, r) == want);
        (want ? inside : outside) += 1;
      }
    }
  }
  CHECK(inside > 1000);
  CHECK(outside > 1000);
  // No walls: nothing is within any reach.
  CHECK_FALSE(any_within({}, 1.0, 1.0, 100.0));
}
