#pragma once
// Shared helpers of the launch-gate tests: keys, verdicts, a two-robot relay
// mission built in code, and a verdict function that answers what the test says.

#include <cstdint>
#include <string>
#include <vector>

#include "mission_builder.hpp"
#include "p3at/hal/team_key.hpp"
#include "p3at/hal/team_link.hpp"
#include "p3at/launch_gate/pre_launch_check.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::test {

/// A key whose bytes are seed, seed+1, ... (distinct seeds → distinct keys).
inline hal::TeamKey gate_key(std::uint8_t seed = 1) {
  hal::TeamKey::Bytes bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(seed + i);
  return hal::TeamKey(bytes);
}

inline const std::string kHashA = std::string(64, 'a');
inline const std::string kHashB = std::string(63, 'a') + "b";

/// A fixed gate nonce per robot name: 32 hex digits, the name's last character
/// (a digit) repeated; `generation` changes it (a restarted process).
inline std::string nonce_of(const std::string& robot, int generation = 0) {
  const char c = static_cast<char>('0' + (robot.back() - '0' + generation) % 10);
  return std::string(32, c);
}

/// `v` having heard `robot`'s gate (nonce_of(robot, generation)).
inline hal::GateVerdict hearing(hal::GateVerdict v, const std::string& robot, int generation = 0) {
  v.heard.push_back({robot, nonce_of(robot, generation)});
  return v;
}

/// `v` committed to `session`.
inline hal::GateVerdict committed(hal::GateVerdict v, const std::string& session) {
  v.session = session;
  return v;
}

/// A verdict with the robot's nonce (nonce_of) and nothing heard yet.
inline hal::GateVerdict verdict(const std::string& robot, hal::GateDecision decision, const std::string& hash = kHashA,
                                double p_joint = 0.9) {
  hal::GateVerdict v;
  v.robot = robot;
  v.nonce = nonce_of(robot);
  v.mission_hash = hash;
  v.decision = decision;
  v.p_time = p_joint;
  v.p_radius = 1.0;
  v.p_joint = p_joint;
  v.threshold = 0.8;
  v.tmax_s = 60.0;
  v.rmax_m = 0.5;
  return v;
}

/// robot1 drives 2 m east and notifies r1_done; robot2 waits for it, then drives 2 m.
inline mission::Mission relay_mission() {
  auto r1 = RobotBuilder("robot1", {1.0, 1.0, 0.0})
                .state("drive", go_to(3.0, 1.0))
                .state("tell", mission::NotifyParams{"r1_done"})
                .state("done", mission::StopParams{})
                .transition("drive", "tell", at_goal(3.0, 1.0, 0.2))
                .transition("tell", "done", mission::MessageSentParams{"r1_done"})
                .build();
  auto r2 = RobotBuilder("robot2", {1.0, 3.0, 0.0})
                .state("wait", mission::StopParams{})
                .state("drive", go_to(3.0, 3.0))
                .state("done", mission::StopParams{})
                .transition("wait", "drive", mission::NotifiedParams{"r1_done"})
                .transition("drive", "done", at_goal(3.0, 3.0, 0.2))
                .build();
  r1.goal = {3.0, 1.0};
  r2.goal = {3.0, 3.0};
  return make_mission({r1, r2}, {mission::Message{"r1_done", 0, {1}}});
}

/// A verdict function that records its calls and answers with `p_joint`
/// (GO when it reaches the threshold), or with `error` when set.
struct ScriptedVerifier {
  double p_joint = 0.9;
  std::optional<Error> error;
  struct Call {
    verifier::VerifyOptions options;
    std::vector<std::string> criteria_files;
    std::optional<verifier::TeamSnapshot> snapshot;
  };
  std::vector<Call> calls;

  gate::VerdictSource source() {
    return [this](const mission::Mission& mission, const verifier::Models&, const verifier::VerifyOptions& options,
                  const std::vector<std::string>& criteria_files,
                  const verifier::TeamSnapshot* from) -> Result<verifier::VerifyResult> {
      calls.push_back(Call{options, criteria_files, from ? std::optional(*from) : std::nullopt});
      if (error) return *error;
      verifier::VerifyResult r;
      r.tmax_s = options.tmax_s.value_or(mission.criteria.tmax_s);
      r.rmax_m = options.rmax_m.value_or(mission.criteria.rmax_m);
      r.threshold = options.threshold.value_or(mission.criteria.threshold);
      r.p_time = p_joint;
      r.p_radius = 1.0;
      r.p_joint = p_joint;
      r.go = p_joint >= r.threshold;
      if (!r.go) r.failed.push_back("P(joint) below threshold (scripted)");
      return r;
    };
  }
};

}  // namespace p3at::test
