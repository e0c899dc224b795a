// NOISE: a world-fixed random direction, held for `persistence` cycles, drawn
// from a generator seeded by (run seed, robot name).

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "p3at/executive/noise.hpp"

using doctest::Approx;
using p3at::exec::NoiseSource;
using p3at::exec::Vec2;

TEST_CASE("noise: a unit direction held for exactly `persistence` cycles") {
  NoiseSource noise(42, "robot1");
  const Vec2<double> first = noise.next(5);
  CHECK(std::hypot(first.x, first.y) == Approx(1.0));
  for (int i = 0; i < 4; ++i) {
    const Vec2<double> again = noise.next(5);
    CHECK(again.x == first.x);
    CHECK(again.y == first.y);
  }
  CHECK(noise.draws() == 1);
  const Vec2<double> second = noise.next(5);  // the 6th cycle redraws
  CHECK(noise.draws() == 2);
  CHECK((second.x != first.x || second.y != first.y));
  CHECK(std::hypot(second.x, second.y) == Approx(1.0));
}

TEST_CASE("noise: restart() forces a fresh draw; persistence below 1 counts as 1") {
  NoiseSource noise(7, "robot2");
  (void)noise.next(10);
  noise.restart();
  (void)noise.next(10);
  CHECK(noise.draws() == 2);
  NoiseSource every(7, "robot2");
  for (int i = 0; i < 4; ++i) (void)every.next(0);
  CHECK(every.draws() == 4);
}

TEST_CASE("noise: deterministic for a (seed, robot) pair, different otherwise") {
  NoiseSource a(123, "robot1"), b(123, "robot1"), other_seed(124, "robot1"), other_robot(123, "robot2");
  int differ_seed = 0, differ_robot = 0;
  for (int i = 0; i < 20; ++i) {
    const Vec2<double> va = a.next(1), vb = b.next(1), vs = other_seed.next(1), vr = other_robot.next(1);
    CHECK(va.x == vb.x);
    CHECK(va.y == vb.y);
    if (va.x != vs.x) ++differ_seed;
    if (va.x != vr.x) ++differ_robot;
  }
  CHECK(differ_seed == 20);
  CHECK(differ_robot == 20);
  CHECK(p3at::exec::noise_seed(1, "robot1") != p3at::exec::noise_seed(1, "robot2"));
  CHECK(p3at::exec::noise_seed(1, "robot1") == p3at::exec::noise_seed(1, "robot1"));
}

TEST_CASE("noise: directions are uniform over the circle") {
  NoiseSource noise(2024, "robot1");
  double sum_x = 0.0, sum_y = 0.0;
  int quadrant[4] = {0, 0, 0, 0};
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec2<double> v = noise.next(1);
    sum_x += v.x;
    sum_y += v.y;
    ++quadrant[(v.x >= 0 ? 0 : 1) + (v.y >= 0 ? 0 : 2)];
  }
  // Standard error of a mean of cos(uniform) over 20000 draws ≈ 0.005.
  CHECK(std::abs(sum_x / n) < 0.02);
  CHECK(std::abs(sum_y / n) < 0.02);
  for (const int q : quadrant) CHECK(std::abs(q - n / 4) < n / 40);
}
