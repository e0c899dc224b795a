// The paper's eq. (7), Success = (r1 <= Rmax) and (r2 <= Rmax) and (t <= Tmax),
// as a criterion: each robot's liveness network (eq. 4) in parallel, its
// finish time bounded by Tmax (so the last one's, the mission's, is too) and
// its true final position within Rmax of its goal.

#include "p3at/verifier/criteria.hpp"

namespace p3at::verifier {

Criterion success_criterion(const mission::Mission& mission, double tmax_s, double rmax_m) {
  Criterion c;
  c.name = "success";
  std::vector<pars::Term> robots;
  Comparison times;
  times.op = pars::CompareOp::less_equal;
  times.right = pars::number(tmax_s);
  std::vector<Constraint> distances;
  for (const mission::RobotSpec& r : mission.robots) {
    const std::string t = "t_" + r.name, w = "w_" + r.name, p = "p_" + r.name;
    robots.push_back(pars::sequence(
        {pars::process("Delay", {pars::name(t)}),
         pars::disabling({pars::process("Delay", {pars::name(w)}), pars::process("At", {pars::name(r.name), pars::name(p)})})}));
    times.left.push_back(pars::name(t));
    Comparison near;
    near.left.push_back(pars::norm(pars::subtract(pars::name(p), pars::point(r.goal.x_m, r.goal.y_m))));
    near.op = pars::CompareOp::less_equal;
    near.right = pars::number(rmax_m);
    distances.push_back(Constraint{{near}, false, pars::CompareOp::greater, 0.0, 0, 0});
  }
  c.network = pars::parallel(std::move(robots));
  if (!times.left.empty()) c.constraints.push_back(Constraint{{times}, false, pars::CompareOp::greater, 0.0, 0, 0});
  for (Constraint& d : distances) c.constraints.push_back(std::move(d));
  return c;
}

}  // namespace p3at::verifier
