#pragma once
/// The robot's body against the walls: a Pioneer 3-AT that drives into a wall
/// stalls there. The simulator (sim_hal's SimRobot) checks the footprint at
/// every physics substep and, where the next substep's footprint would overlap
/// a wall or another robot, moves nothing and zeroes the firmware's
/// velocities; the base ramps up again from rest at the next substep. The
/// verifier holds its paths against the walls only (StateContext::walls says
/// why not against teammates). Without this the
/// verifier's paths drove through a wall's end that every run stalls against
/// (generated gen_7462: 1,000 of 1,000 runs pinned on leg4 at the end of a
/// free-standing wall, verify P(success) 1.000; docs/verifier.md, "The body
/// against the walls").

#include <vector>

#include "engine/base_motion.hpp"
#include "engine/sonar_model.hpp"

namespace p3at::verifier::engine {

/// Whether the P3-AT's footprint (kBodyHalfLengthM x kBodyHalfWidthM about
/// its centre, along its heading) at the pose (x, y, theta) overlaps a segment.
bool body_touches(const std::vector<Segment>& segments, double x_m, double y_m, double theta_rad);

/// How far from the body's centre a segment may be and still be touched
/// within one cycle: the footprint's half-diagonal plus what a corner can
/// travel in the cycle (at top_speed_mps and top_rot_radps), with a
/// centimetre to spare. Anything farther cannot be met within the cycle, and
/// there step_cycle() gives what step_cycle_against() would, to the bit.
double contact_reach_m(double top_speed_mps, double top_rot_radps, double cycle_s);

/// step_cycle() with the body against the walls: the base's odometric pose q
/// moves the true pose q + error_mean, and a substep that would take the
/// footprint there into a segment does not happen (both velocities set to
/// zero, as the simulator's stall). The model's mean path may be inside a
/// wall already where no run is (the walker reduction merges paths on either
/// side of a wall's end and restores their spread about the mean): such a
/// path may move out or along, but not drive its centre deeper in, so it
/// neither sticks where no run could be nor passes through. `stalled`
/// (optional) is set when a substep was held.
CycleIncrement step_cycle_against(BaseState& base, double command_trans_mps, double command_rot_radps,
                                  const Kinematics& kinematics, const std::vector<Segment>& segments,
                                  const double error_mean[3], bool* stalled = nullptr);

}  // namespace p3at::verifier::engine
