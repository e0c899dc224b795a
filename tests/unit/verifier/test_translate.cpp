// The FSA → PARS translator (docs/pars.md, "The translation") on the Bounding
// Overwatch example and on generated missions: structure, round trip through
// the printer and parser, abort conditions per state, and the composed system.

#include <doctest/doctest.h>

#include <string>

#include "p3at/mission/loader.hpp"
#include "p3at/verifier/pars/abort_condition.hpp"
#include "p3at/verifier/pars/parser.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/translate.hpp"

namespace pars = p3at::verifier::pars;
namespace mission = p3at::mission;
using p3at::verifier::translate;
using pars::Op;

namespace {

const mission::Mission& bounding_overwatch() {
  static const mission::Mission m =
      mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/mission.yaml");
  return m;
}

const pars::Definition& def(const pars::Program& p, const std::string& name) {
  const pars::Definition* d = p.find(name);
  REQUIRE_MESSAGE(d != nullptr, "no definition " << name);
  return *d;
}

// Three robots; a state with two ways out, a loop back, a Spin with an offset turn.
constexpr const char* kPatrol = R"(mission:
  name: patrol
criteria: {tmax_s: 300, rmax_m: 1.0, threshold: 0.5}
robots:
  - name: scout
    start: {x_m: 0, y_m: 0}
    hal: tcp://127.0.0.1:8101
    states:
      - {name: out, behavior: GoToGuarded, params: {goal: [5, 0]}}
      - {name: back, behavior: GoToGuarded, params: {goal: [0, 0], noise_gain: 0}}
      - {name: look, behavior: Spin, params: {rate_deg_s: -30}}
      - {name: report, behavior: Notify, params: {message: seen}}
      - {name: home, behavior: Stop}
    transitions:
      - {from: out, to: look, trigger: AtGoal, params: {radius_m: 0.5}}
      - {from: out, to: back, trigger: Notified, params: {message: recall}}
      - {from: look, to: report, trigger: HasTurned, params: {angle_deg: 180, offset_deg: 10}}
      - {from: report, to: out, trigger: MessageSent}
      - {from: back, to: home, trigger: AtGoal, params: {radius_m: 0.5}}
  - name: base
    start: {x_m: -1, y_m: 0, theta_deg: 90}
    hal: tcp://127.0.0.1:8102
    states:
      - {name: wait, behavior: Stop}
      - {name: call, behavior: Notify, params: {message: recall}}
      - {name: idle, behavior: Stop}
    transitions:
      - {from: wait, to: call, trigger: Notified, params: {message: seen}}
      - {from: call, to: idle, trigger: MessageSent}
  - name: loner
    start: {x_m: 3, y_m: 3}
    hal: tcp://127.0.0.1:8103
    states:
      - {name: sit, behavior: Stop}
messages:
  - {name: seen, from: scout, to: [base, loner]}
  - {name: recall, from: base, to: [scout]}
)";

}  // namespace

TEST_SUITE("translate: Bounding Overwatch") {
  TEST_CASE("every state of every robot is a definition robot.state") {
    const pars::Program p = translate(bounding_overwatch());
    std::size_t states = 0;
    for (const auto& robot : bounding_overwatch().robots) {
      for (const auto& state : robot.states) {
        CHECK(p.find(robot.name + "." + state.name) != nullptr);
        ++states;
      }
    }
    CHECK(states == 19);
    // Plus Mission, Robot, Env, Comm and Sys.
    CHECK(p.definitions.size() == states + 5);
    for (const char* name : {"Mission", "Robot", "Env", "Comm", "Sys"}) CHECK(p.find(name) != nullptr);
  }

  TEST_CASE("Mission starts every robot in its initial state, with all the robots' ports") {
    const pars::Program p = translate(bounding_overwatch());
    const pars::Definition& m = def(p, "Mission");
    CHECK(pars::to_string(m.body) == "robot1.overwatch_start | robot2.bound_ow1");
    CHECK(m.in_ports.front() == "od_robot1");
    CHECK(m.out_ports == std::vector<std::string>{"v_robot1", "v_robot2", "put_r2_at_ow1", "put_r1_at_ow2",
                                                  "put_r2_at_ow3", "put_r1_at_goal"});
  }

  TEST_CASE("GoToGuarded is the Coop of Move_to, Avoid_Obstacles and Noise, with the mission's parameters") {
    const pars::Program p = translate(bounding_overwatch());
    const pars::Term& body = def(p, "robot1.bound_ow2").body;
    REQUIRE(body.op == Op::disabling);
    REQUIRE(body.parts.size() == 2);
    const pars::Term& network = body.parts[0];
    REQUIRE(network.op == Op::parallel);
    REQUIRE(network.parts.size() == 4);
    CHECK(pars::to_string(network.parts[0]) ==
          "Coop<1, 1, 0.135, 0.3>(robot1.bound_ow2.move, robot1.bound_ow2.avoid, robot1.bound_ow2.noise)(v_robot1)");
    CHECK(pars::to_string(network.parts[1]) == "Move_to<(13, 4), 0.5, 0.05>(od_robot1)(robot1.bound_ow2.move)");
    CHECK(pars::to_string(network.parts[2]) ==
          "Avoid_Obstacles<0.5, 0.25>(od_robot1, ob_robot1)(robot1.bound_ow2.avoid)");
    CHECK(pars::to_string(network.parts[3]) == "Noise<600>(od_robot1)(robot1.bound_ow2.noise)");
    // The trigger in sequence with the next state.
    CHECK(pars::to_string(body.parts[1]) == "Is_at_goal<(13, 4), 0.3>(od_robot1) ; robot1.tell_at_ow2");
  }

  TEST_CASE("triggers are condition processes; Notify puts its message; a final state is its network") {
    const pars::Program p = translate(bounding_overwatch());
    CHECK(pars::to_string(def(p, "robot1.overwatch_start").body) ==
          "Stop()(v_robot1) # Got_message<r2_at_ow1>(msg_r2_at_ow1) ; robot1.bound_ow2");
    CHECK(pars::to_string(def(p, "robot1.tell_at_ow2").body) ==
          "Put_message<r1_at_ow2>()(put_r1_at_ow2) | Stop()(v_robot1) # "
          "Message_sent<r1_at_ow2>(ack_r1_at_ow2) ; robot1.overwatch_ow2");
    CHECK(pars::to_string(def(p, "robot2.turn_left").body) ==
          "Spin<40>()(v_robot2) # Has_turned<90, 0>(od_robot2) ; robot2.bound_goal");
    CHECK(pars::to_string(def(p, "robot2.done").body) == "Stop()(v_robot2)");
    CHECK(def(p, "robot2.done").comment == "robot2.done: Stop (final state)");
    CHECK(def(p, "robot2.bound_ow1").comment ==
          "robot2.bound_ow1: GoToGuarded to (10, 6) (initial state)\n  on AtGoal within 0.3 m of (10, 6) -> tell_at_ow1");
  }

  TEST_CASE("each state's abort condition Ω is its trigger's condition") {
    const pars::Program p = translate(bounding_overwatch());
    const auto omega = [&](const std::string& name) { return pars::to_string(pars::abort_condition(def(p, name))); };
    CHECK(omega("robot1.overwatch_start") == "received(msg_r2_at_ow1)");
    CHECK(omega("robot1.bound_ow2") == "|od_robot1 - (13, 4)| <= 0.3");
    CHECK(omega("robot1.tell_at_ow2") == "acked(ack_r1_at_ow2)");
    CHECK(omega("robot1.turn_left") == "turned(od_robot1) >= 90");
    CHECK(omega("robot1.bound_goal") == "|od_robot1 - (19.75, 18)| <= 0.3");
    CHECK(omega("robot1.done") == "never");
    CHECK(omega("robot2.bound_goal") == "|od_robot2 - (20, 17.5)| <= 0.3");
  }

  TEST_CASE("the robot template is tail-recursive, as the paper's Robot_{r,q}") {
    const pars::Program p = translate(bounding_overwatch());
    const pars::Definition& robot = def(p, "Robot");
    CHECK(pars::is_tail_recursive(robot));
    CHECK(pars::header_string(robot) == "Robot<n, r, q, t, Z>(v)(p, od)");
    CHECK(pars::to_string(robot.body) ==
          "(At<n, r> # Delay<t> # Out<p, r> # Out<od, q> # In<v, u>) ; "
          "Robot<n, r + u * z(u, t, Z) * t, q + u * t, t, Z>(v)(p, od)");
    CHECK(pars::to_string(def(p, "Env").body) ==
          "Sonar<W, R>(p_robot1, p_robot2)(ob_robot1) | Sonar<W, R>(p_robot2, p_robot1)(ob_robot2)");
    CHECK(def(p, "Comm").body.parts.size() == 4);
  }

  TEST_CASE("Sys composes Mission, the robots, Env and Comm; every port has one writer") {
    const pars::Program p = translate(bounding_overwatch());
    const auto sys = p3at::verifier::compose_system(p);
    REQUIRE_MESSAGE(sys.ok(), (sys.ok() ? "" : sys.error().message));
    REQUIRE(sys->components.size() == 5);
    CHECK(sys->components[0].label == "Mission");
    CHECK(sys->components[1].label == "Robot<robot1>");
    CHECK(sys->components[3].label == "Env");
    CHECK(sys->components[4].label == "Comm");
    CHECK(sys->components[1].tail_recursive);
    CHECK_FALSE(sys->components[0].tail_recursive);
    // Mission reads 2 ports per robot and 2 per message; robots 1 each; Env 2; Comm 4.
    CHECK(sys->connections.size() == 12 + 2 + 2 + 4);
    CHECK(sys->feeders(0) == std::vector<std::size_t>{1, 3, 2, 4});
    CHECK(sys->feeders(1) == std::vector<std::size_t>{0});
    // The robots' flow: odometry advances by the commanded velocity the Mission writes.
    const auto* q = sys->find_flow("Robot<robot1>", "q");
    REQUIRE(q != nullptr);
    CHECK(pars::to_string(q->initial) == "(5.5, 5, 0)");
    CHECK(pars::to_string(q->update) == "(5.5, 5, 0) + v_robot1 * t_robot1");
    CHECK(q->ports == std::vector<std::string>{"v_robot1"});
  }

  TEST_CASE("the printed program parses back to the same program") {
    const pars::Program p = translate(bounding_overwatch());
    const std::string text = pars::to_string(p);
    CHECK(pars::parse_program(text, "bo.pars") == p);
    // Close to the paper's listing: each GoToGuarded network parenthesised, '#' ending its line.
    CHECK(text.find("     Noise<600>(od_robot1)(robot1.bound_ow2.noise)) #\n"
                    "    (Is_at_goal<(13, 4), 0.3>(od_robot1) ; robot1.tell_at_ow2)\n") != std::string::npos);
  }
}

TEST_SUITE("translate: models and generated missions") {
  TEST_CASE("with models: control period, motion error, walls, range and delays as values") {
    p3at::verifier::Models models;
    models.source = "m.yaml";
    for (const auto& robot : bounding_overwatch().robots) {
      p3at::verifier::RobotModel rm;
      rm.name = robot.name;
      rm.kinematics.cycle_s = 0.1;
      rm.motion.trans_scale = 0.909;
      rm.motion.trans_var_per_m = 0.25;
      // robot2's wheels differ: its turns move it forward (the last argument).
      if (robot.name == "robot2") rm.motion.trans_per_rad_m = 0.0075;
      models.robots.push_back(rm);
    }
    models.environment.walls.push_back({3, 2.5, 24, 2.5});
    models.environment.sonar_max_range_m = 4.5;
    models.comm.delivery_s.components = {{0.9, 0.007, 1e-5}, {0.1, 0.16, 0.008}};
    models.comm.ack_s.components = {{1.0, 0.013, 2.5e-5}};
    const auto p = translate(bounding_overwatch(), models);
    REQUIRE(p.ok());
    const pars::Term& sys = def(*p, "Sys").body;
    CHECK(pars::to_string(sys.parts[1]) ==
          "Robot<robot1, (5.5, 5, 0), (5.5, 5, 0), 0.1, Motion(0.909, 1, 0, 0.25, 0, 0, 0)>(v_robot1)(p_robot1, od_robot1)");
    CHECK(pars::to_string(sys.parts[2]).find("Motion(0.909, 1, 0, 0.25, 0, 0, 0.0075)") != std::string::npos);
    CHECK(pars::to_string(sys.parts[3].params[0]) == "((3, 2.5, 24, 2.5),)");
    CHECK(sys.parts[3].params[1] == pars::number(4.5));
    CHECK(pars::to_string(sys.parts[4].params[0]) == "MoG((0.9, 0.007, 1e-05), (0.1, 0.16, 0.008))");
    CHECK(pars::parse_program(pars::to_string(*p)) == *p);
    // A robot the models do not describe is an error that names it.
    models.robots.pop_back();
    const auto missing = translate(bounding_overwatch(), models);
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().message == "no model for robot 'robot2' in m.yaml (it describes robot1)");
  }

  TEST_CASE("several ways out of a state: one disabling branch each, in the order they are checked") {
    const mission::Mission m = mission::parse_mission(kPatrol, "patrol.yaml");
    const pars::Program p = translate(m);
    const pars::Term& out = def(p, "scout.out").body;
    REQUIRE(out.parts.size() == 3);
    CHECK(pars::to_string(out.parts[1]) == "Is_at_goal<(5, 0), 0.5>(od_scout) ; scout.look");
    CHECK(pars::to_string(out.parts[2]) == "Got_message<recall>(msg_recall) ; scout.back");
    CHECK(pars::to_string(pars::abort_condition(def(p, "scout.out"))) ==
          "|od_scout - (5, 0)| <= 0.5 or received(msg_recall)");
    CHECK(pars::to_string(pars::abort_condition(def(p, "scout.look"))) == "turned(od_scout) >= 170");
    CHECK(pars::to_string(def(p, "scout.look").body.parts[0]) == "Spin<-30>()(v_scout)");
    // The loop back to 'out' is a call like any other.
    CHECK(pars::to_string(def(p, "scout.report").body.parts[1]) == "Message_sent<seen>(ack_seen) ; scout.out");
    CHECK(pars::to_string(def(p, "Mission").body) == "scout.out | base.wait | loner.sit");
    CHECK(pars::parse_program(pars::to_string(p)) == p);
    // Three robots: each sonar sees the other two.
    CHECK(pars::to_string(def(p, "Env").body.parts[2]) == "Sonar<W, R>(p_loner, p_scout, p_base)(ob_loner)");
    const auto sys = p3at::verifier::compose_system(p);
    REQUIRE(sys.ok());
    CHECK(sys->components.size() == 6);
  }

  TEST_CASE("a mission without messages has no Comm") {
    mission::Mission m = mission::parse_mission(kPatrol, "patrol.yaml");
    m.robots.resize(1);
    m.robots[0].states.resize(1);
    m.robots[0].states[0].outgoing.clear();
    m.robots[0].transitions.clear();
    m.messages.clear();
    const pars::Program p = translate(m);
    CHECK(p.find("Comm") == nullptr);
    CHECK(pars::to_string(def(p, "Sys").body.parts.back()) == "Env<Walls, R_sonar>(p_scout)(ob_scout)");
    CHECK(p3at::verifier::compose_system(p).ok());
  }

  TEST_CASE("the relay example translates and round-trips") {
    const mission::Mission m = mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/examples/relay/mission.yaml");
    const pars::Program p = translate(m);
    CHECK(pars::parse_program(pars::to_string(p)) == p);
    CHECK(p3at::verifier::compose_system(p).ok());
  }
}
