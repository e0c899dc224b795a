// The body against the walls (engine/body_contact.hpp): the verifier's paths
// stall where the simulator's robot would, its footprint (626 x 505 mm) held
// at a wall instead of driven through it, and a path the model placed inside a
// wall may leave it but not go deeper.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/base_motion.hpp"
#include "engine/body_contact.hpp"

using namespace p3at::verifier;
using namespace p3at::verifier::engine;

namespace {

constexpr double kPi = 3.14159265358979323846;

Kinematics kinematics() {
  Kinematics k;
  k.cycle_s = 0.1;
  k.max_rot_vel_radps = 0.75;
  k.trans_accel_mps2 = 0.3;
  k.trans_decel_mps2 = 0.6;
  k.rot_accel_radps2 = 1.75;
  k.rot_decel_radps2 = 1.75;
  return k;
}

// A wall across the x axis at x = wall_x, from y = -1 to 1.
std::vector<Segment> wall_at(double wall_x) { return {Segment{wall_x, -1.0, wall_x, 1.0}}; }

const double kNoError[3] = {0.0, 0.0, 0.0};

}  // namespace

TEST_CASE("the footprint touches a wall exactly where its outline reaches it") {
  // Facing +x, the front face is 0.313 m ahead of the centre, the sides 0.2525 m.
  CHECK_FALSE(body_touches(wall_at(0.314), 0.0, 0.0, 0.0));
  CHECK(body_touches(wall_at(0.312), 0.0, 0.0, 0.0));
  CHECK(body_touches(wall_at(-0.312), 0.0, 0.0, 0.0));  // the back face
  // Turned a quarter, the wall ahead meets a side instead.
  CHECK_FALSE(body_touches(wall_at(0.26), 0.0, 0.0, kPi / 2.0));
  CHECK(body_touches(wall_at(0.25), 0.0, 0.0, kPi / 2.0));
  // A wall's end: the segment from (0.2, 0) toward +x pokes into the front.
  const std::vector<Segment> end{Segment{0.2, 0.0, 2.0, 0.0}};
  CHECK(body_touches(end, 0.0, 0.0, 0.0));
  CHECK_FALSE(body_touches(end, -0.12, 0.0, 0.0));
  // Beside the body, level with it but off to the side.
  const std::vector<Segment> beside{Segment{-1.0, 0.3, 1.0, 0.3}};
  CHECK_FALSE(body_touches(beside, 0.0, 0.0, 0.0));
  CHECK(body_touches(beside, 0.0, 0.06, 0.0));
  // A short segment wholly inside the footprint.
  const std::vector<Segment> inside{Segment{-0.05, 0.0, 0.05, 0.0}};
  CHECK(body_touches(inside, 0.0, 0.0, 0.3));
  // A corner: rotated 45 degrees the half-diagonal (0.4026 m) reaches out.
  const double corner = std::hypot(0.313, 0.2525);
  const double to_corner = std::atan2(0.2525, 0.313);
  CHECK(body_touches(wall_at(corner - 0.002), 0.0, 0.0, -to_corner));
  CHECK_FALSE(body_touches(wall_at(corner + 0.002), 0.0, 0.0, -to_corner));
  CHECK_FALSE(body_touches({}, 0.0, 0.0, 0.0));
}

TEST_CASE("away from every wall, the stepping against walls is the plain step, to the bit") {
  const Kinematics k = kinematics();
  BaseState plain{1.0, 2.0, 0.4, 0.25, 0.1};
  BaseState against = plain;
  const std::vector<Segment> far{Segment{10.0, -1.0, 10.0, 1.0}};
  for (int cycle = 0; cycle < 30; ++cycle) {
    const CycleIncrement a = step_cycle(plain, 0.4, -0.2, k);
    bool stalled = true;
    const CycleIncrement b = step_cycle_against(against, 0.4, -0.2, k, far, kNoError, &stalled);
    CHECK_FALSE(stalled);
    CHECK(a.ds_m == b.ds_m);
    CHECK(a.dtheta_rad == b.dtheta_rad);
    CHECK(a.mid_theta_rad == b.mid_theta_rad);
  }
  CHECK(plain.x_m == against.x_m);
  CHECK(plain.y_m == against.y_m);
  CHECK(plain.theta_rad == against.theta_rad);
  CHECK(plain.trans_mps == against.trans_mps);
  CHECK(plain.rot_radps == against.rot_radps);
  // How far a wall can be and still be met within a cycle at 0.6 m/s and
  // 0.75 rad/s: the half-diagonal 0.4026 m, 6 cm of travel, 3 cm of a
  // corner's swing, a centimetre to spare.
  CHECK(contact_reach_m(0.6, 0.75, 0.1) == doctest::Approx(0.4026 + 0.06 + 0.0302 + 0.01).epsilon(1e-3));
  // A body that close to a wall, one cycle at full speed from it, is held there.
  BaseState q{0.0, 0.0, 0.0, 0.6, 0.0};
  const double gap = contact_reach_m(0.6, 0.0, 0.1) - 0.01 - std::hypot(0.313, 0.2525);  // 6 cm
  bool stalled = false;
  step_cycle_against(q, 0.6, 0.0, k, wall_at(0.313 + gap - 0.01), kNoError, &stalled);
  CHECK(stalled);
}

TEST_CASE("driving head-on into a wall, the base stalls at it and stays") {
  const Kinematics k = kinematics();
  BaseState q{0.0, 0.0, 0.0, 0.4, 0.0};
  const std::vector<Segment> wall = wall_at(1.0);
  bool ever = false;
  for (int cycle = 0; cycle < 40; ++cycle) {
    bool stalled = false;
    step_cycle_against(q, 0.4, 0.0, k, wall, kNoError, &stalled);
    ever = ever || stalled;
  }
  CHECK(ever);
  // The front face within one substep (4 mm at 0.4 m/s) of the wall, never past it.
  CHECK(q.x_m + 0.313 <= 1.0 + 1e-9);
  CHECK(q.x_m + 0.313 > 1.0 - 0.005);
  CHECK(q.trans_mps < 0.01);  // stalled: the ramp restarts from rest every substep
  // Turning on the spot is held too when the turn would swing a corner into it.
  const double before = q.theta_rad;
  step_cycle_against(q, 0.0, 0.5, k, wall, kNoError);
  CHECK(q.theta_rad == doctest::Approx(before).epsilon(1e-3));
  // Backing off is free.
  const double x = q.x_m;
  for (int cycle = 0; cycle < 5; ++cycle) step_cycle_against(q, -0.2, 0.0, k, wall, kNoError);
  CHECK(q.x_m < x - 0.02);
}

TEST_CASE("the true pose, not the odometric one, meets the wall") {
  const Kinematics k = kinematics();
  // The odometry believes the robot 0.5 m short of where it is.
  const double error[3] = {0.5, 0.0, 0.0};
  BaseState q{0.0, 0.0, 0.0, 0.0, 0.0};
  for (int cycle = 0; cycle < 40; ++cycle) step_cycle_against(q, 0.4, 0.0, k, wall_at(1.5), error);
  CHECK(q.x_m + 0.5 + 0.313 <= 1.5 + 1e-9);
  CHECK(q.x_m + 0.5 + 0.313 > 1.5 - 0.005);
}

TEST_CASE("a path that starts inside a wall may turn, move out or along it, never drive deeper") {
  const Kinematics k = kinematics();
  // The front face 5 cm past a wall (where a merged mean path can be).
  const std::vector<Segment> wall = wall_at(0.263);
  BaseState deeper{0.0, 0.0, 0.0, 0.0, 0.0};
  bool stalled = false;
  step_cycle_against(deeper, 0.3, 0.0, k, wall, kNoError, &stalled);
  CHECK(stalled);
  CHECK(deeper.x_m == 0.0);
  BaseState out{0.0, 0.0, 0.0, 0.0, 0.0};
  for (int cycle = 0; cycle < 5; ++cycle) step_cycle_against(out, -0.3, 0.0, k, wall, kNoError);
  CHECK(out.x_m < -0.03);
  // Along the wall (facing +y, the wall 5 cm into its side): as deep all the way.
  BaseState along{0.0, 0.0, kPi / 2.0, 0.0, 0.0};
  const std::vector<Segment> side = wall_at(0.2025);
  for (int cycle = 0; cycle < 5; ++cycle) step_cycle_against(along, 0.3, 0.0, k, side, kNoError);
  CHECK(along.y_m > 0.03);
  // Turning on the spot moves no centre: free, though a corner swings deeper in.
  BaseState turning{0.0, 0.0, 0.0, 0.0, 0.0};
  for (int cycle = 0; cycle < 5; ++cycle) step_cycle_against(turning, 0.0, 0.5, k, wall, kNoError);
  CHECK(turning.theta_rad > 0.1);
}
