// The model processes of Sys (docs/pars.md, "The translation"): the robot
// template (the paper's Robot_{r,q}), the sensor/environment process and the
// communication process, and their instances with symbolic or model values.

#include <utility>

#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/translate.hpp"
#include "translate/translate_parts.hpp"

namespace p3at::verifier::detail {

namespace {

using pars::Expr;
using pars::Term;
namespace m = mission;

Expr pose_of(const m::Pose2& p) {
  return pars::tuple({pars::number(p.x_m), pars::number(p.y_m), pars::number(p.theta_deg)});
}

Expr mixture_expr(const Mixture1& x) {
  std::vector<Expr> components;
  for (const Component1& c : x.components) {
    components.push_back(pars::tuple({pars::number(c.weight), pars::number(c.mean), pars::number(c.var)}));
  }
  return pars::call("MoG", std::move(components));
}

}  // namespace

Term robot_instance(const m::RobotSpec& robot, const RobotModel* model) {
  Expr period = pars::name("t_" + robot.name);
  Expr motion = pars::name("Z_" + robot.name);
  if (model != nullptr) {
    period = pars::number(model->kinematics.cycle_s);
    const MotionError& z = model->motion;
    motion = pars::call("Motion", {pars::number(z.trans_scale), pars::number(z.rot_scale), pars::number(z.drift_rad_per_m),
                                   pars::number(z.trans_var_per_m), pars::number(z.rot_var_per_rad),
                                   pars::number(z.heading_var_per_m), pars::number(z.trans_per_rad_m)});
  }
  // The odometry starts where the robot truly is: both poses from `start`.
  return pars::process("Robot", {pars::name(robot.name), pose_of(robot.start), pose_of(robot.start), period, motion},
                       {names::velocity_port(robot.name)},
                       {names::pose_port(robot.name), names::odometry_port(robot.name)});
}

pars::Definition robot_template() {
  // Robot<n, r, q, t, Z>(v)(p, od) = (At<n, r> # Delay<t> # Out<p, r> # Out<od, q> # In<v, u>) ;
  //                                  Robot<n, r + u * z(u, t, Z) * t, q + u * t, t, Z>(v)(p, od)
  pars::Definition d;
  d.name = "Robot";
  d.params = {"n", "r", "q", "t", "Z"};
  d.in_ports = {"v"};
  d.out_ports = {"p", "od"};
  d.comment =
      "The robot model (the paper's Robot_{r,q}): robot n at true pose r believes it is at q (odometry);\n"
      "each control period t it shows its true pose on p and its odometry on od, reads the velocity u\n"
      "commanded on v, and moves: q by u * t, r by u * z(u, t, Z) * t, where z is the motion error\n"
      "that calibration measured (Z). Poses are (x m, y m, heading deg).";
  const Expr u = pars::name("u");
  const Expr t = pars::name("t");
  Term period = pars::disabling({
      pars::process("At", {pars::name("n"), pars::name("r")}),
      pars::process("Delay", {t}),
      pars::process("Out", {pars::name("p"), pars::name("r")}),
      pars::process("Out", {pars::name("od"), pars::name("q")}),
      pars::process("In", {pars::name("v"), u}),
  });
  Expr next_r = pars::add(pars::name("r"),
                          pars::multiply(pars::multiply(u, pars::call("z", {u, t, pars::name("Z")})), t));
  Expr next_q = pars::add(pars::name("q"), pars::multiply(u, t));
  Term recursion = pars::process("Robot", {pars::name("n"), next_r, next_q, t, pars::name("Z")}, {"v"}, {"p", "od"});
  d.body = pars::sequence({std::move(period), std::move(recursion)});
  return d;
}

pars::Definition environment_definition(const m::Mission& mission) {
  // Each robot's sonar ring sees the walls and the other robots.
  pars::Definition d;
  d.name = "Env";
  d.params = {"W", "R"};
  d.comment =
      "The sensor and environment model: each robot's sonar ring reads the walls W and the other\n"
      "robots up to range R, from the robots' true poses, and gives that robot its obstacles.";
  std::vector<Term> sonars;
  for (std::size_t i = 0; i < mission.robots.size(); ++i) {
    const std::string& me = mission.robots[i].name;
    d.in_ports.push_back(names::pose_port(me));
    d.out_ports.push_back(names::obstacles_port(me));
    std::vector<std::string> poses{names::pose_port(me)};
    for (std::size_t j = 0; j < mission.robots.size(); ++j) {
      if (j != i) poses.push_back(names::pose_port(mission.robots[j].name));
    }
    sonars.push_back(
        pars::process("Sonar", {pars::name("W"), pars::name("R")}, std::move(poses), {names::obstacles_port(me)}));
  }
  d.body = pars::parallel(std::move(sonars));
  return d;
}

Term environment_instance(const m::Mission& mission, const Environment* environment) {
  Expr walls = pars::name("Walls");
  Expr range = pars::name("R_sonar");
  if (environment != nullptr) {
    std::vector<Expr> segments;
    for (const Wall& w : environment->walls) {
      segments.push_back(
          pars::tuple({pars::number(w.x0_m), pars::number(w.y0_m), pars::number(w.x1_m), pars::number(w.y1_m)}));
    }
    walls = pars::tuple(std::move(segments));
    range = pars::number(environment->sonar_max_range_m);
  }
  Term t = pars::process("Env", {walls, range});
  for (const m::RobotSpec& r : mission.robots) {
    t.in_ports.push_back(names::pose_port(r.name));
    t.out_ports.push_back(names::obstacles_port(r.name));
  }
  return t;
}

pars::Definition comm_definition(const m::Mission& mission) {
  pars::Definition d;
  d.name = "Comm";
  d.params = {"D", "A"};
  d.comment =
      "The team link: a message put by its sender reaches its recipients after the delay D and\n"
      "its acknowledgement reaches the sender after A (both random).";
  std::vector<Term> channels;
  for (const m::Message& msg : mission.messages) {
    d.in_ports.push_back(names::put_port(msg.name));
    d.out_ports.push_back(names::delivery_port(msg.name));
    d.out_ports.push_back(names::ack_port(msg.name));
    channels.push_back(pars::process("Channel", {pars::name(msg.name), pars::name("D"), pars::name("A")},
                                     {names::put_port(msg.name)},
                                     {names::delivery_port(msg.name), names::ack_port(msg.name)}));
  }
  d.body = pars::parallel(std::move(channels));
  return d;
}

Term comm_instance(const m::Mission& mission, const CommModel* comm) {
  Expr delivery = pars::name("Delivery");
  Expr ack = pars::name("Ack");
  if (comm != nullptr) {
    delivery = mixture_expr(comm->delivery_s);
    ack = mixture_expr(comm->ack_s);
  }
  Term t = pars::process("Comm", {delivery, ack});
  for (const m::Message& msg : mission.messages) {
    t.in_ports.push_back(names::put_port(msg.name));
    t.out_ports.push_back(names::delivery_port(msg.name));
    t.out_ports.push_back(names::ack_port(msg.name));
  }
  return t;
}

std::string system_comment(const m::Mission& mission, const Models* models) {
  std::string c = "Sys: the Mission process with the robot, sensor/environment";
  c += mission.messages.empty() ? " models" : " and communication models";
  c += ", connected by port names.";
  if (models == nullptr) {
    c += "\nSymbols stand for the models' values (vipars translate --models FILE fills them in):\n"
         "t_<robot> control period, Z_<robot> motion error, Walls, R_sonar sonar range";
    if (!mission.messages.empty()) c += ", Delivery and Ack message delays";
    c += ".";
    return c;
  }
  c += "\nModels from " + models->source + ": Motion(trans_scale, rot_scale, drift_rad_per_m, trans_var_per_m,\n"
       "rot_var_per_rad, heading_var_per_m, trans_per_rad_m); MoG((weight, mean s, variance s^2), ...); walls (x0, y0, x1, y1).";
  for (const m::RobotSpec& r : mission.robots) {
    for (const RobotModel& model : models->robots) {
      if (model.name != r.name) continue;
      const Kinematics& k = model.kinematics;
      c += "\n" + r.name + "'s base: max rotation " + pars::format_number(k.max_rot_vel_radps) + " rad/s, acceleration " +
           pars::format_number(k.trans_accel_mps2) + " m/s^2, deceleration " + pars::format_number(k.trans_decel_mps2) +
           " m/s^2, max speed " + pars::format_number(r.max_speed_mps) + " m/s.";
    }
  }
  return c;
}

}  // namespace p3at::verifier::detail
