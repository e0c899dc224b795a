#pragma once
/// The launch gate's verdicts (docs/launch-gate.md): what each robot decided
/// before launch, as the gate publishes it on the team link, and the link that
/// carries them. The executive's hal::TeamLink knows nothing of them: the
/// team link's implementations (DatagramTeamLink, over LCM or the simulated
/// radio) are VerdictLinks, and only the launch gate uses that side.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/result.hpp"
#include "p3at/hal/team_link.hpp"

namespace p3at::gate {

/// A launch-gate decision as published on the team link (docs/launch-gate.md).
enum class GateDecision {
  go,           ///< the verifier's probability meets the threshold and every criterion holds
  no_go,        ///< it does not: no robot of the team may move
  override_go,  ///< the operator overrode this robot's decision with --override-gate
};
/// "GO", "NO-GO", "OVERRIDE" (the wire spelling).
constexpr const char* to_string(GateDecision decision) {
  switch (decision) {
    case GateDecision::go: return "GO";
    case GateDecision::no_go: return "NO-GO";
    case GateDecision::override_go: return "OVERRIDE";
  }
  return "?";
}
/// Inverse of to_string(GateDecision); nullopt for anything else (case-sensitive).
constexpr std::optional<GateDecision> gate_decision_from_string(std::string_view text) {
  for (const GateDecision d : {GateDecision::go, GateDecision::no_go, GateDecision::override_go}) {
    if (text == to_string(d)) return d;
  }
  return std::nullopt;
}
/// True for the decisions that let the team launch (GO and OVERRIDE).
constexpr bool allows_launch(GateDecision decision) { return decision != GateDecision::no_go; }

/// A teammate's gate nonce, as heard by the robot that publishes a verdict.
struct HeardNonce {
  std::string robot;
  std::string nonce;
  bool operator==(const HeardNonce&) const = default;
};

/// One robot's launch-gate verdict (authenticated like everything else).
/// The last three fields make the launch an agreement of this very run
/// (docs/launch-gate.md): `nonce` is fresh for every gate, `heard` echoes the
/// teammates' nonces the sender has heard, `session` is set once the sender
/// has committed to launching with exactly those teammates.
struct GateVerdict {
  std::string robot;         ///< the sender (set by the link when publishing)
  std::string mission_hash;  ///< 64 lowercase hex digits: what the verdict is about
  GateDecision decision = GateDecision::no_go;
  double p_time = -1.0;      ///< P(done by tmax_s); < 0 when unknown
  double p_radius = -1.0;    ///< P(every robot within rmax_m of its goal); < 0 when unknown
  double p_joint = -1.0;     ///< P(both); < 0 when unknown
  double threshold = 0.0;    ///< the launch threshold applied
  double tmax_s = 0.0;       ///< the criteria applied
  double rmax_m = 0.0;
  std::string detail;        ///< failed criteria, or why overridden
  std::string nonce;         ///< 32 lowercase hex digits, random, one per gate (empty only in tests of old code paths)
  std::string session;       ///< "" until committed; then the session id (64 lowercase hex digits)
  std::vector<HeardNonce> heard;  ///< teammates' nonces the sender has heard, at most one per teammate
};

/// A team link that also carries the gate's verdicts.
class VerdictLink : public hal::TeamLink {
 public:
  /// Publishes this robot's launch-gate verdict (best effort, not
  /// acknowledged: the gate republishes it until the team has agreed).
  virtual Status publish_verdict(const GateVerdict& verdict) = 0;
  /// The latest authenticated gate verdict of each teammate that has sent one.
  virtual const std::vector<GateVerdict>& teammate_verdicts() const = 0;
};

}  // namespace p3at::gate
