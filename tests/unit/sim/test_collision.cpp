// Collisions: a wall or another robot stops the robot, sets the stall flags,
// and the robot can back away; the broad phases that skip far obstacles
// never skip a real contact or echo.

#include <doctest/doctest.h>

#include <cmath>
#include <span>

#include "p3at/sim/p3at_model.hpp"
#include "p3at/sim/rng.hpp"
#include "sim_test_util.hpp"

using namespace p3at::sim;
using p3at::sim::test::exact_robot;
using p3at::sim::test::run_for;
using p3at::sim::test::world_of;

TEST_CASE("driving into a wall stalls the robot in front of it") {
  World world(world_of({exact_robot()}, {{{1.0, -2.0}, {1.0, 2.0}}}));
  SimRobot& robot = world.robot(0);
  robot.controller().enable_motors(true);
  robot.controller().command_trans_vel(0.3);
  run_for(world, 6.0);
  const double front = robot.true_pose().x_m + kP3atLengthM / 2.0;
  CHECK(front <= 1.0);
  CHECK(front > 0.99);
  CHECK(robot.left_stall());
  CHECK(robot.right_stall());
  CHECK(robot.true_trans_vel_mps() == doctest::Approx(0.0));
  // The wheels stopped: odometry did not run on past the wall.
  CHECK(robot.odometry().x_m == doctest::Approx(robot.true_pose().x_m).epsilon(1e-9));

  robot.controller().command_trans_vel(-0.2);
  run_for(world, 1.0);
  CHECK_FALSE(robot.left_stall());
  CHECK(robot.true_pose().x_m + kP3atLengthM / 2.0 < 0.95);
}

TEST_CASE("turning a corner into a wall also stalls") {
  // A wall alongside the robot's left, just clear of its corners.
  World world(world_of({exact_robot()}, {{{-2.0, 0.27}, {2.0, 0.27}}}));
  SimRobot& robot = world.robot(0);
  robot.controller().enable_motors(true);
  robot.controller().command_rot_vel(0.5);
  run_for(world, 2.0);
  CHECK(robot.left_stall());
  CHECK(robot.true_pose().theta_rad < 0.2);
}

TEST_CASE("robots do not pass through each other") {
  World world(world_of({exact_robot("a", 0.0, 0.0, 0.0), exact_robot("b", 2.0, 0.0, 180.0)}));
  for (std::size_t i = 0; i < 2; ++i) {
    world.robot(i).controller().enable_motors(true);
    world.robot(i).controller().command_trans_vel(0.3);
  }
  run_for(world, 6.0);
  const double gap = world.robot(1).true_pose().x_m - world.robot(0).true_pose().x_m - kP3atLengthM;
  CHECK(gap >= 0.0);
  CHECK(gap < 0.02);
  CHECK(world.robot(0).left_stall());
  CHECK(world.robot(1).right_stall());
}

TEST_CASE("footprint overlap: crossing edges, containment either way, separation") {
  const Footprint big{{0.0, 0.0, 0.0}, 2.0, 2.0};
  const Footprint small{{0.3, 0.2, 0.7}, 0.4, 0.3};
  CHECK(intersects(big, small));
  CHECK(intersects(small, big));
  const Footprint apart{{2.0, 0.0, 0.0}, 0.5, 0.5};
  CHECK_FALSE(intersects(big, apart));
  // A square 0.6 m on a side turned 45°: its corner reaches 0.424 m from its centre.
  CHECK(intersects(big, Footprint{{1.40, 0.0, 0.785398}, 0.6, 0.6}));
  CHECK_FALSE(intersects(big, Footprint{{1.45, 0.0, 0.785398}, 0.6, 0.6}));
  CHECK(intersects(big, Segment{{-0.5, 0.0}, {0.5, 0.0}}));  // wholly inside
  CHECK_FALSE(intersects(big, Segment{{1.5, -3.0}, {1.5, 3.0}}));
}

TEST_CASE("the broad phases never reject what the exact tests accept") {
  // Random segments, boxes and rays around the origin: segment_within agrees
  // with the squared distance, and a ray that meets a box's edges always
  // passes ray_may_hit (the sonar's test against the bounding circle).
  Rng rng(17, 0);
  const auto coord = [&] { return rng.uniform() * 6.0 - 3.0; };
  int box_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Segment s{{coord(), coord()}, {coord(), coord()}};
    const Vec2 p{coord(), coord()};
    const double r = rng.uniform() * 2.0;
    const double d_sq = distance_sq_to_segment(p, s.a, s.b);
    if (std::abs(d_sq - r * r) > 1e-9) CHECK(segment_within(p, s, r) == (d_sq <= r * r));

    const Box box = to_box(Footprint{{coord(), coord(), rng.uniform() * 6.3}, 0.626, 0.505});
    const double heading = rng.uniform() * 6.3;
    const Vec2 dir{std::cos(heading), std::sin(heading)};
    Segment edges[4];
    box_edges(box, edges);
    const double range = rng.uniform() * 5.0;
    double nearest = range;
    bool hit = false;
    for (const Segment& e : edges) hit = ray_hit(p, dir, e, nearest) || hit;
    if (hit) {
      ++box_hits;
      CHECK(ray_may_hit(p, dir, box, range));
      CHECK(ray_cast_dir(p, dir, std::span<const Segment>(edges, 4), range).value() == nearest);
    }
  }
  CHECK(box_hits > 500);  // the random cases did exercise hits (807 with this seed)
}
