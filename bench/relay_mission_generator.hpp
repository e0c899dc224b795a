#pragma once
/// Relay missions of any size, for the verifier's scaling benchmark
/// (bench_verifier): k robots in parallel lanes pass a token round a ring.
///
/// Robot i's lane is y = 2 + 2i (2 m apart, more than the 1.15 m within which
/// AVOID_OBSTACLES reacts, so lanes do not push each other); every robot starts
/// at x = 2 facing +X. One token trip: robot 0 bounds 2.5 m along its lane
/// (GoToGuarded with NOISE), notifies robot 1, which bounds and notifies
/// robot 2, ..., robot k-1 notifies robot 0. Per trip each robot has four
/// states:
///   robot i > 0:  wait (Stop, Notified by i-1) -> bound -> tell (Notify i+1) -> scan
///   robot 0:      bound -> tell (Notify 1) -> scan -> wait (Notified by k-1)
/// where scan is a full 360° Spin (HasTurned 360) that overlaps the next
/// robot's bound, so robots move concurrently as well as in sequence. In the
/// last trip scan is replaced by the final `done` Stop (robot 0: its wait leads
/// to `done`), so m states per robot means m / 4 trips, exactly m states.
///
/// The mission is written as YAML and parsed by the project's loader, so it is
/// a valid, fully resolved Mission (a generator bug shows up as a MissionError).

#include <cstddef>
#include <string>

#include "p3at/mission/mission.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::bench {

/// The relay mission's YAML text. Requires robots >= 2 and states_per_robot a
/// positive multiple of 4; throws std::invalid_argument otherwise.
std::string relay_mission_yaml(std::size_t robots, std::size_t states_per_robot);

/// relay_mission_yaml() parsed by mission::parse_mission.
mission::Mission relay_mission(std::size_t robots, std::size_t states_per_robot);

/// Robot models for a relay mission: one RobotModel per mission robot with a
/// small systematic and random motion error (a few per cent, varying from
/// robot to robot), a fast team link (small Gaussian delivery and ack delays)
/// and, as the environment, an open rectangle of four walls around every lane.
verifier::Models relay_models(const mission::Mission& relay);

}  // namespace p3at::bench
