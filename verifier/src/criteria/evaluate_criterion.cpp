// Evaluating a criterion on the system's final distribution (the seed
// paper's section V): project, match structurally, bind, then compute each
// constraint group's probability branch by branch.

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <utility>

#include "criteria/events.hpp"
#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/mog.hpp"
#include "p3at/verifier/pars/equivalence.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/pars/projection.hpp"

namespace p3at::verifier {

namespace {

using pars::Expr;
using pars::Term;

// What a system parameter of the projected trace stands for.
struct Symbol {
  enum class Kind { finish, wait, position };
  Kind kind = Kind::finish;
  std::size_t robot = 0;
};

std::string symbol_name(Symbol::Kind kind, const std::string& robot) {
  switch (kind) {
    case Symbol::Kind::finish: return "T_" + robot;
    case Symbol::Kind::wait: return "W_" + robot;
    case Symbol::Kind::position: return "P_" + robot;
  }
  return robot;
}

// A robot's last period as the system runs it (the robot template's period,
// after n - 1 periods grouped into one Delay):
//   Delay<T> ; (Delay<W> # At<r, P> # Out<p_r, P> # Out<od_r, Q> # In<v_r, U>)
Term robot_trace(const std::string& robot) {
  return pars::sequence(
      {pars::process("Delay", {pars::name(symbol_name(Symbol::Kind::finish, robot))}),
       pars::disabling({pars::process("Delay", {pars::name(symbol_name(Symbol::Kind::wait, robot))}),
                        pars::process("At", {pars::name(robot), pars::name(symbol_name(Symbol::Kind::position, robot))}),
                        pars::process("Out", {pars::name("p_" + robot), pars::name("P_" + robot)}),
                        pars::process("Out", {pars::name("od_" + robot), pars::name("Q_" + robot)}),
                        pars::process("In", {pars::name("v_" + robot), pars::name("U_" + robot)})})});
}

std::string format_probability(double p) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", p);
  return buffer;
}

struct Group {
  std::string text;                 // what it requires, for the explanation
  std::vector<detail::Event> events;
  double required = 0.0;
  bool strict = false;              // '>' rather than '>='
  double probability = 0.0;
};

class Evaluator {
 public:
  Evaluator(const Criterion& c, const mission::Mission& m, const SystemOutcome& o) : c_(c), m_(m), o_(o) {}

  Result<CriterionVerdict> run(double default_required) {
    const std::string where = c_.source.empty() ? "criterion '" + c_.name + "'"
                                                : "criterion '" + c_.name + "' (" + c_.source + ")";
    // The robots the criterion names, in its order.
    std::vector<std::string> robot_names;
    pars::for_each_process(c_.network, [&](const Term& p) {
      if (p.name == "At" && !p.params.empty() && p.params[0].kind == pars::ExprKind::name &&
          std::find(robot_names.begin(), robot_names.end(), p.params[0].name) == robot_names.end()) {
        robot_names.push_back(p.params[0].name);
      }
    });
    if (robot_names.empty()) {
      return make_error(Error::Code::invalid_argument,
                        where + " names no robot: its network needs At<robot, position> for each robot it constrains");
    }
    std::vector<Term> traces;
    for (const std::string& r : robot_names) {
      const auto index = m_.find_robot(r);
      if (!index) {
        std::string known;
        for (const auto& spec : m_.robots) known += (known.empty() ? "" : ", ") + spec.name;
        return make_error(Error::Code::invalid_argument,
                          where + ": unknown robot '" + r + "' (the mission has " + known + ")");
      }
      robots_.push_back(*index);
      for (const auto kind : {Symbol::Kind::finish, Symbol::Kind::wait, Symbol::Kind::position}) {
        symbols_[symbol_name(kind, r)] = Symbol{kind, *index};
      }
      traces.push_back(robot_trace(r));
    }
    // Project the system onto the criterion's processes and match it (Def. 7).
    const Term system = pars::parallel(std::move(traces));
    const std::set<std::string> names = pars::process_names(c_.network);
    const auto projected = pars::project(system, names);
    if (!projected) {
      return make_error(Error::Code::invalid_argument,
                        where + ": none of its processes occurs in the system (it offers Delay and At)");
    }
    const pars::StructuralMatch match = pars::structurally_equivalent(*projected, c_.network);
    if (!match.equivalent) {
      return make_error(Error::Code::invalid_argument,
                        where + " does not match the system's structure: " + match.mismatch +
                            ". The system projected onto the criterion's processes is " + pars::to_string(*projected));
    }
    for (const pars::ParameterBinding& b : match.bindings) {
      // left: the system's parameter, right: the criterion's.
      if (b.left.kind != pars::ExprKind::name || b.right.kind != pars::ExprKind::name) continue;
      const auto symbol = symbols_.find(b.left.name);
      if (symbol == symbols_.end()) {
        if (b.left.name != b.right.name) {
          return make_error(Error::Code::invalid_argument, where + ": " + b.process + "'s parameter '" + b.right.name +
                                                               "' does not match the system's '" + b.left.name + "'");
        }
        continue;
      }
      bound_[b.right.name] = symbol->second;
    }
    // The constraint groups.
    std::vector<Group> groups;
    Group bare;
    bare.required = default_required;
    for (const Constraint& k : c_.constraints) {
      Group g;
      Group& target = k.probabilistic ? g : bare;
      for (const Comparison& comparison : k.events) {
        std::vector<detail::Event> events;
        std::string problem;
        if (!detail::classify(comparison, kinds(), events, problem)) {
          return make_error(Error::Code::invalid_argument, where + ": " + problem);
        }
        for (const detail::Event& e : events) {
          for (const std::string* var : {&e.a, &e.b}) {
            if (var->empty()) continue;
            if (auto status = check_bound(*var, where); !status) return status.error();
          }
        }
        target.events.insert(target.events.end(), events.begin(), events.end());
      }
      if (k.probabilistic) {
        Constraint inner = k;
        inner.probabilistic = false;
        g.text = "P(" + to_string(inner) + ")";
        g.required = k.bound;
        g.strict = k.bound_op == pars::CompareOp::greater;
        groups.push_back(std::move(g));
      } else {
        bare.text += (bare.text.empty() ? "" : " and ") + to_string(k);
      }
    }
    if (!bare.events.empty() || groups.empty()) {
      bare.text = bare.text.empty() ? "P(the network is reached)" : "P(" + bare.text + ")";
      groups.insert(groups.begin(), std::move(bare));
    }
    for (Group& g : groups) g.probability = probability(g.events);
    return verdict(groups, where);
  }

 private:
  detail::VariableKinds kinds() const {
    detail::VariableKinds k;
    pars::for_each_process(c_.network, [&](const Term& p) {
      if (p.params.empty() || p.params.back().kind != pars::ExprKind::name) return;
      k[p.params.back().name] = p.name == "Delay" ? detail::VariableKind::time : detail::VariableKind::position;
    });
    return k;
  }

  Status check_bound(const std::string& var, const std::string& where) const {
    const auto it = bound_.find(var);
    if (it == bound_.end()) {
      return make_error(Error::Code::invalid_argument, where + ": variable '" + var + "' is not bound to the system");
    }
    if (it->second.kind == Symbol::Kind::wait) {
      return make_error(Error::Code::invalid_argument,
                        where + ": '" + var + "' is how long " + m_.robots[it->second.robot].name +
                            " stays at its final position (the Delay beside its At); the verifier does not give "
                            "its distribution, so it cannot be constrained");
    }
    return {};
  }

  const RobotOutcome& robot(const Branch& b, const std::string& var) const {
    return b.robots[bound_.at(var).robot];
  }

  // P(event) in one branch.
  double event_probability(const Branch& b, const detail::Event& e) const {
    switch (e.kind) {
      case detail::Event::Kind::time_bound: {
        const double below = robot(b, e.a).finish_time_s.cdf(e.value - e.offset);
        return detail::is_less(e.op) ? below : 1.0 - below;
      }
      case detail::Event::Kind::time_order: {
        const Mixture1 a = shifted(robot(b, e.a).finish_time_s, e.offset);
        const Mixture1& other = robot(b, e.b).finish_time_s;
        return detail::is_less(e.op) ? probability_less(a, other) : probability_less(other, a);
      }
      case detail::Event::Kind::distance_to_point: {
        const double within =
            final_within(robot(b, e.a), Eigen::Vector2d(e.x, e.y), e.value);
        return detail::is_less(e.op) ? within : 1.0 - within;
      }
      case detail::Event::Kind::distance_between: {
        // Safety (eq. 6): at every sampled moment of the branch and at the end.
        const std::size_t i = bound_.at(e.a).robot, j = bound_.at(e.b).robot;
        const auto sample = [&](const Gaussian2& difference) {
          const double within = probability_within(difference, Eigen::Vector2d::Zero(), e.value);
          return detail::is_less(e.op) ? within : 1.0 - within;
        };
        Gaussian2 last;
        last.mean = b.robots[i].final_position.mean - b.robots[j].final_position.mean;
        last.cov = b.robots[i].final_position.cov + b.robots[j].final_position.cov;
        double p = sample(last);
        for (const SeparationSample& s : b.separations) {
          if ((s.robot_i == i && s.robot_j == j) || (s.robot_i == j && s.robot_j == i)) p = std::min(p, sample(s.difference));
        }
        return p;
      }
    }
    return 0.0;
  }

  double probability(const std::vector<detail::Event>& events) const {
    double total = 0.0;
    for (const Branch& b : o_.branches) {
      if (b.robots.size() != m_.robots.size()) continue;
      // A robot that never gets to its At in this branch cannot match the network.
      bool finished = true;
      for (const std::size_t r : robots_) finished = finished && b.robots[r].finished;
      if (!finished) continue;
      double p = 1.0;
      for (const detail::Event& e : events) p *= event_probability(b, e);
      total += b.weight * std::clamp(p, 0.0, 1.0);
    }
    return std::clamp(total, 0.0, 1.0);
  }

  Result<CriterionVerdict> verdict(const std::vector<Group>& groups, const std::string& where) const {
    for (const Branch& b : o_.branches) {
      if (b.robots.size() != m_.robots.size()) {
        return make_error(Error::Code::invalid_argument, where + ": the outcome has " + std::to_string(b.robots.size()) +
                                                             " robots in a branch, the mission " +
                                                             std::to_string(m_.robots.size()));
      }
    }
    CriterionVerdict v;
    v.name = c_.name;
    v.holds = true;
    std::optional<std::size_t> worst;
    std::string explanation;
    for (std::size_t i = 0; i < groups.size(); ++i) {
      const Group& g = groups[i];
      const bool holds = g.strict ? g.probability > g.required : g.probability >= g.required;
      v.holds = v.holds && holds;
      if (!worst || g.probability - g.required < groups[*worst].probability - groups[*worst].required) worst = i;
      explanation += (explanation.empty() ? "" : "; ") + g.text + " = " + format_probability(g.probability) +
                     (holds ? ", holds (" : ", fails (") + "required " + (g.strict ? "> " : ">= ") +
                     format_probability(g.required) + ")";
    }
    v.probability = groups[*worst].probability;
    v.required = groups[*worst].required;
    const double lost = o_.pruned_mass + o_.blocked_mass + o_.loop_cutoff_mass;
    if (lost > 0.0) {
      explanation += "; pruned and blocked mass " + format_probability(lost) + " counts as failure";
    }
    v.explanation = explanation;
    return v;
  }

  const Criterion& c_;
  const mission::Mission& m_;
  const SystemOutcome& o_;
  std::vector<std::size_t> robots_;
  std::map<std::string, Symbol> symbols_;
  std::map<std::string, Symbol> bound_;
};

}  // namespace

Result<CriterionVerdict> evaluate_criterion(const Criterion& criterion, const mission::Mission& mission,
                                            const SystemOutcome& outcome, double default_required_probability) {
  return Evaluator(criterion, mission, outcome).run(default_required_probability);
}

}  // namespace p3at::verifier
