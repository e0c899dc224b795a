// The Mission process: each robot's FSA as PARS (docs/pars.md, "The translation").
// A state becomes a named definition: its behavior's process network, disabled
// by each outgoing trigger's condition process in sequence with the next state,
//   robot1.s = Network # (Condition1 ; robot1.next1) # (Condition2 ; robot1.next2)
// (the first condition to hold stops the network and starts its next state;
// ties go to the transition listed first, as in the executive).

#include <utility>
#include <variant>

#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/translate.hpp"
#include "translate/translate_parts.hpp"

namespace p3at::verifier::detail {

namespace {

using pars::Term;
namespace m = mission;

pars::Expr point_of(const m::Point2& p) { return pars::point(p.x_m, p.y_m); }

std::string point_text(const m::Point2& p) { return pars::to_string(point_of(p)); }

const std::string& message_name(const m::Mission& mission, std::size_t index) { return mission.messages[index].name; }

// What each behavior does, as its CNL network of basic processes.
Term behavior_network(const m::RobotSpec& robot, const m::State& state) {
  const std::string v = names::velocity_port(robot.name);
  const std::string od = names::odometry_port(robot.name);
  const std::string ob = names::obstacles_port(robot.name);
  switch (state.kind()) {
    case m::BehaviorKind::go_to_guarded: {
      // The paper's Figure 2: GoToGuarded = Coop of Move_to, Avoid_Obstacles and Noise,
      // connected through ports local to this state.
      const auto& p = std::get<m::GoToGuardedParams>(state.behavior);
      const std::string local = names::state_process(robot, state);
      const std::string move = local + ".move", avoid = local + ".avoid", noise = local + ".noise";
      return pars::parallel({
          pars::process("Coop",
                        {pars::number(p.move_gain), pars::number(p.avoid_gain), pars::number(p.noise_gain),
                         pars::number(robot.max_speed_mps)},
                        {move, avoid, noise}, {v}),
          pars::process("Move_to", {point_of(p.goal), pars::number(p.dropoff_m), pars::number(p.dead_zone_m)}, {od},
                        {move}),
          pars::process("Avoid_Obstacles", {pars::number(p.sphere_m), pars::number(p.safety_margin_m)}, {od, ob},
                        {avoid}),
          pars::process("Noise", {pars::number(static_cast<double>(p.noise_persistence_cycles))}, {od}, {noise}),
      });
    }
    case m::BehaviorKind::spin: {
      const auto& p = std::get<m::SpinParams>(state.behavior);
      return pars::process("Spin", {pars::number(p.rate_deg_s)}, {}, {v});
    }
    case m::BehaviorKind::stop: return pars::process("Stop", {}, {}, {v});
    case m::BehaviorKind::notify: {
      const auto& p = std::get<m::NotifyParams>(state.behavior);
      return pars::parallel({pars::process("Put_message", {pars::name(p.message)}, {}, {names::put_port(p.message)}),
                             pars::process("Stop", {}, {}, {v})});
    }
  }
  return pars::process("Stop", {}, {}, {v});
}

// A trigger as the condition process that reads what it watches.
Term trigger_condition(const m::RobotSpec& robot, const m::Transition& transition) {
  const std::string od = names::odometry_port(robot.name);
  switch (transition.kind()) {
    case m::TriggerKind::at_goal: {
      const auto& p = std::get<m::AtGoalParams>(transition.trigger);
      return pars::process("Is_at_goal", {point_of(p.goal), pars::number(p.radius_m)}, {od});
    }
    case m::TriggerKind::has_turned: {
      const auto& p = std::get<m::HasTurnedParams>(transition.trigger);
      return pars::process("Has_turned", {pars::number(p.angle_deg), pars::number(p.offset_deg)}, {od});
    }
    case m::TriggerKind::notified: {
      const auto& p = std::get<m::NotifiedParams>(transition.trigger);
      return pars::process("Got_message", {pars::name(p.message)}, {names::delivery_port(p.message)});
    }
    case m::TriggerKind::message_sent: {
      const auto& p = std::get<m::MessageSentParams>(transition.trigger);
      return pars::process("Message_sent", {pars::name(p.message)}, {names::ack_port(p.message)});
    }
  }
  return pars::process("Never");
}

std::string describe_behavior(const m::State& state) {
  switch (state.kind()) {
    case m::BehaviorKind::go_to_guarded:
      return "GoToGuarded to " + point_text(std::get<m::GoToGuardedParams>(state.behavior).goal);
    case m::BehaviorKind::spin:
      return "Spin at " + pars::format_number(std::get<m::SpinParams>(state.behavior).rate_deg_s) + " deg/s";
    case m::BehaviorKind::stop: return "Stop";
    case m::BehaviorKind::notify: return "Notify " + std::get<m::NotifyParams>(state.behavior).message;
  }
  return "?";
}

std::string describe_trigger(const m::Transition& t) {
  switch (t.kind()) {
    case m::TriggerKind::at_goal: {
      const auto& p = std::get<m::AtGoalParams>(t.trigger);
      return "AtGoal within " + pars::format_number(p.radius_m) + " m of " + point_text(p.goal);
    }
    case m::TriggerKind::has_turned: {
      const auto& p = std::get<m::HasTurnedParams>(t.trigger);
      std::string text = "HasTurned " + pars::format_number(p.angle_deg) + " deg";
      if (p.offset_deg != 0.0) text += " (offset " + pars::format_number(p.offset_deg) + " deg)";
      return text;
    }
    case m::TriggerKind::notified: return "Notified " + std::get<m::NotifiedParams>(t.trigger).message;
    case m::TriggerKind::message_sent: return "MessageSent " + std::get<m::MessageSentParams>(t.trigger).message;
  }
  return "?";
}

pars::Definition state_definition(const m::RobotSpec& robot, std::size_t index) {
  const m::State& state = robot.states[index];
  pars::Definition d;
  d.name = names::state_process(robot, state);
  d.comment = d.name + ": " + describe_behavior(state);
  if (index == robot.initial) d.comment += " (initial state)";
  if (state.outgoing.empty()) d.comment += " (final state)";
  std::vector<Term> parts{behavior_network(robot, state)};
  for (const std::size_t t : state.outgoing) {
    const m::Transition& transition = robot.transitions[t];
    const m::State& next = robot.states[transition.to];
    parts.push_back(pars::sequence({trigger_condition(robot, transition),
                                    pars::process(names::state_process(robot, next))}));
    d.comment += "\n  on " + describe_trigger(transition) + " -> " + next.name;
  }
  d.body = pars::disabling(std::move(parts));
  return d;
}

}  // namespace

std::vector<std::string> mission_in_ports(const m::Mission& mission) {
  std::vector<std::string> ports;
  for (const m::RobotSpec& r : mission.robots) {
    ports.push_back(names::odometry_port(r.name));
    ports.push_back(names::obstacles_port(r.name));
  }
  for (std::size_t i = 0; i < mission.messages.size(); ++i) ports.push_back(names::delivery_port(message_name(mission, i)));
  for (std::size_t i = 0; i < mission.messages.size(); ++i) ports.push_back(names::ack_port(message_name(mission, i)));
  return ports;
}

std::vector<std::string> mission_out_ports(const m::Mission& mission) {
  std::vector<std::string> ports;
  for (const m::RobotSpec& r : mission.robots) ports.push_back(names::velocity_port(r.name));
  for (std::size_t i = 0; i < mission.messages.size(); ++i) ports.push_back(names::put_port(message_name(mission, i)));
  return ports;
}

std::vector<pars::Definition> mission_definitions(const m::Mission& mission) {
  std::vector<pars::Definition> defs;
  pars::Definition top;
  top.name = "Mission";
  top.in_ports = mission_in_ports(mission);
  top.out_ports = mission_out_ports(mission);
  top.comment = "Mission '" + mission.name + "': every robot's FSA from its initial state (the paper's Mission, VI.A).";
  std::vector<Term> robots;
  for (const m::RobotSpec& r : mission.robots) robots.push_back(pars::process(names::state_process(r, r.initial_state())));
  top.body = pars::parallel(std::move(robots));
  defs.push_back(std::move(top));
  for (const m::RobotSpec& r : mission.robots) {
    for (std::size_t i = 0; i < r.states.size(); ++i) defs.push_back(state_definition(r, i));
  }
  return defs;
}

}  // namespace p3at::verifier::detail
