#include "params.hpp"

#include <string>
#include <vector>

namespace p3at::mission::detail {
namespace {

const Range kDistanceRange{0.0, 1000.0};            // radii and margins, m
const Range kPositiveDistanceRange{0.0, 1000.0, true, false};
const Range kGainRange{0.0, 1000.0};
constexpr double kMaxSpinRateDegS = 360.0;
constexpr double kMaxTurnDeg = 3600.0;
constexpr std::int64_t kMaxPersistenceCycles = 1'000'000;

std::vector<std::string> names_of(std::initializer_list<const char*> names) {
  return std::vector<std::string>(names.begin(), names.end());
}

// The `params` mapping, or an empty stand-in located at the behavior/trigger name.
MapReader params_of(const MapReader& owner, const std::string& where, const YAML::Mark& kind_mark,
                    const std::vector<std::string>& allowed) {
  if (!owner.has("params")) return MapReader::empty(owner.source(), kind_mark, where, "parameter");
  return owner.params("params", where, allowed);
}

GoToGuardedParams parse_go_to_guarded(const MapReader& p) {
  GoToGuardedParams g;
  g.goal = read_point(p, "goal", kCoordinateRange);
  g.dropoff_m = p.number_or("dropoff_m", kDistanceRange, g.dropoff_m);
  g.dead_zone_m = p.number_or("dead_zone_m", kDistanceRange, g.dead_zone_m);
  g.move_gain = p.number_or("move_gain", kGainRange, g.move_gain);
  g.avoid_gain = p.number_or("avoid_gain", kGainRange, g.avoid_gain);
  g.noise_gain = p.number_or("noise_gain", kGainRange, g.noise_gain);
  g.sphere_m = p.number_or("sphere_m", kPositiveDistanceRange, g.sphere_m);
  g.safety_margin_m = p.number_or("safety_margin_m", kDistanceRange, g.safety_margin_m);
  g.noise_persistence_cycles =
      p.integer_or("noise_persistence_cycles", 1, kMaxPersistenceCycles, g.noise_persistence_cycles);
  // MOVE_TO_GUARDED ramps its gain from the dropoff edge down to the dead-zone
  // edge, which needs the dead zone inside the dropoff radius.
  if (g.dropoff_m < g.dead_zone_m) {
    const bool at_dropoff = p.has("dropoff_m");
    p.source().fail(p.value_mark(at_dropoff ? "dropoff_m" : "dead_zone_m"),
                    "'dropoff_m' (" + format_shortest(g.dropoff_m) + ") must not be less than 'dead_zone_m' (" +
                        format_shortest(g.dead_zone_m) + ")");
  }
  return g;
}

SpinParams parse_spin(const MapReader& p) {
  SpinParams s;
  s.rate_deg_s = p.number("rate_deg_s", Range{-kMaxSpinRateDegS, kMaxSpinRateDegS});
  if (s.rate_deg_s == 0.0) {
    p.source().fail(p.value_mark("rate_deg_s"), "'rate_deg_s' must not be 0 (a Spin that never turns; use Stop)");
  }
  return s;
}

}  // namespace

BehaviorParams parse_behavior(const MapReader& state, BehaviorKind kind, const YAML::Mark& kind_mark,
                              YAML::Mark& message_mark) {
  const std::string where = "for behavior " + std::string(to_string(kind));
  switch (kind) {
    case BehaviorKind::go_to_guarded:
      return parse_go_to_guarded(params_of(
          state, where, kind_mark,
          names_of({"goal", "dropoff_m", "dead_zone_m", "move_gain", "avoid_gain", "noise_gain", "sphere_m",
                    "safety_margin_m", "noise_persistence_cycles"})));
    case BehaviorKind::spin:
      return parse_spin(params_of(state, where, kind_mark, names_of({"rate_deg_s"})));
    case BehaviorKind::stop:
      (void)params_of(state, where, kind_mark, {});
      return StopParams{};
    case BehaviorKind::notify: {
      const MapReader p = params_of(state, where, kind_mark, names_of({"message"}));
      NotifyParams n{read_name(p, "message", "message")};
      message_mark = p.value_mark("message");
      return n;
    }
  }
  return StopParams{};
}

namespace {

AtGoalParams parse_at_goal(const MapReader& p, const State& source) {
  AtGoalParams a;
  a.radius_m = p.number("radius_m", kPositiveDistanceRange);
  const auto* go = std::get_if<GoToGuardedParams>(&source.behavior);
  if (p.has("goal")) {
    a.goal = read_point(p, "goal", kCoordinateRange);
  } else if (go != nullptr) {
    a.goal = go->goal;
  } else {
    p.source().fail(p.mark(), "missing required parameter 'goal' for trigger AtGoal (source state '" + source.name +
                                  "' runs " + std::string(to_string(source.kind())) +
                                  ", not GoToGuarded, so there is no goal to default to)");
  }
  // GoToGuarded stops pushing inside its dead zone: a success radius inside it
  // could leave the robot parked short of the goal with the trigger never firing.
  if (go != nullptr && go->goal == a.goal && a.radius_m <= go->dead_zone_m) {
    p.source().fail(p.value_mark("radius_m"),
                    "'radius_m' (" + format_shortest(a.radius_m) + ") must exceed the source state's 'dead_zone_m' (" +
                        format_shortest(go->dead_zone_m) + "), or the robot may stop before it arrives");
  }
  return a;
}

HasTurnedParams parse_has_turned(const MapReader& p) {
  HasTurnedParams h;
  h.angle_deg = p.number("angle_deg", Range{0.0, kMaxTurnDeg, true, false});
  h.offset_deg = p.number_or("offset_deg", Range{0.0, h.angle_deg, false, true}, h.offset_deg);
  return h;
}

bool sends(const RobotSpec& robot, const std::string& message) {
  for (const State& s : robot.states) {
    const auto* n = std::get_if<NotifyParams>(&s.behavior);
    if (n != nullptr && n->message == message) return true;
  }
  return false;
}

MessageSentParams parse_message_sent(const MapReader& p, const YAML::Mark& kind_mark, const RobotSpec& robot,
                                     const State& source, YAML::Mark& message_mark) {
  MessageSentParams m;
  if (p.has("message")) {
    m.message = read_name(p, "message", "message");
    message_mark = p.value_mark("message");
    if (!sends(robot, m.message)) {
      p.source().fail(message_mark, "MessageSent on message '" + m.message + "' that robot '" + robot.name +
                                        "' never sends (it has no Notify state for it)");
    }
  } else if (const auto* n = std::get_if<NotifyParams>(&source.behavior)) {
    m.message = n->message;
    message_mark = kind_mark;
  } else {
    p.source().fail(p.mark(), "missing required parameter 'message' for trigger MessageSent (source state '" +
                                  source.name + "' runs " + std::string(to_string(source.kind())) +
                                  ", not Notify, so there is no message to default to)");
  }
  return m;
}

}  // namespace

TriggerParams parse_trigger(const MapReader& transition, TriggerKind kind, const YAML::Mark& kind_mark,
                            const RobotSpec& robot, const State& source, YAML::Mark& message_mark) {
  const std::string where = "for trigger " + std::string(to_string(kind));
  switch (kind) {
    case TriggerKind::at_goal:
      return parse_at_goal(params_of(transition, where, kind_mark, names_of({"goal", "radius_m"})), source);
    case TriggerKind::has_turned:
      return parse_has_turned(params_of(transition, where, kind_mark, names_of({"angle_deg", "offset_deg"})));
    case TriggerKind::notified: {
      const MapReader p = params_of(transition, where, kind_mark, names_of({"message"}));
      NotifiedParams n{read_name(p, "message", "message")};
      message_mark = p.value_mark("message");
      return n;
    }
    case TriggerKind::message_sent:
      return parse_message_sent(params_of(transition, where, kind_mark, names_of({"message"})), kind_mark, robot,
                                source, message_mark);
  }
  return NotifiedParams{};
}

}  // namespace p3at::mission::detail
