// Evaluating a criterion on the system's final distribution (the seed
// paper's section V): project, match structurally, bind, then compute each
// constraint group's probability branch by branch.

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <map>
#include <optional>
#include <utility>

#include "criteria/events.hpp"
#include "engine/time_position.hpp"
#include "p3at/common/number_format.hpp"
#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/mog.hpp"
#include "p3at/verifier/pars/equivalence.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/pars/projection.hpp"
#include "p3at/verifier/separation.hpp"

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

std::string format_probability(double p) { return format_general(p, 4); }

struct Group {
  std::string text;                 // what it requires, for the explanation
  std::vector<detail::Event> events;
  double required = 0.0;
  bool strict = false;              // '>' rather than '>='
  double probability = 0.0;
};

class Evaluator {
 public:
  Evaluator(const Criterion& c, const mission::Mission& m, const SystemOutcome& o, double separation_step_m)
      : c_(c), m_(m), o_(o), separation_step_m_(separation_step_m) {}

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
        // Eq. (6) read as "at all times": over the pair's positions at the
        // same mission times along the branch (separation.hpp: one common
        // error per stretch of seconds, Boole over stretches, a lower bound),
        // decided with the gate's margin.
        const std::size_t i = bound_.at(e.a).robot, j = bound_.at(e.b).robot;
        const bool apart = !detail::is_less(e.op);
        const double d = decided_separation(e.value, apart, separation_step_m_);
        return apart ? probability_always_apart(b, i, j, d) : probability_always_within(b, i, j, d);
      }
    }
    return 0.0;
  }

  static bool is_time(const detail::Event& e) {
    return e.kind == detail::Event::Kind::time_bound || e.kind == detail::Event::Kind::time_order;
  }

  /// P(every time event) in one branch, the robots' finish times being
  /// independent mixtures. Events are split into groups that share no
  /// variable (independent, so their probabilities multiply); within a
  /// group, each variable but the last is integrated out on a grid of
  /// cells of exact probability (evaluated at each cell's conditional
  /// mean), and the last one's events become an interval of its CDF. A
  /// group of more than three robots' times falls back to the Fréchet lower
  /// bound max(0, sum P - (n - 1)): conservative, never optimistic.
  double joint_time_probability(const Branch& b, const std::vector<detail::Event>& events) const {
    std::vector<const detail::Event*> time_events;
    for (const detail::Event& e : events) {
      if (is_time(e)) time_events.push_back(&e);
    }
    if (time_events.empty()) return 1.0;
    // Variables (robot indices) and connected groups.
    std::vector<std::size_t> group(time_events.size());
    for (std::size_t i = 0; i < group.size(); ++i) group[i] = i;
    const auto root = [&](std::size_t i) {
      while (group[i] != i) i = group[i];
      return i;
    };
    const auto shares = [&](const detail::Event& x, const detail::Event& y) {
      const auto vars = [&](const detail::Event& e) {
        std::vector<std::size_t> v{bound_.at(e.a).robot};
        if (e.kind == detail::Event::Kind::time_order) v.push_back(bound_.at(e.b).robot);
        return v;
      };
      for (const std::size_t u : vars(x)) {
        for (const std::size_t w : vars(y)) {
          if (u == w) return true;
        }
      }
      return false;
    };
    for (std::size_t i = 0; i < time_events.size(); ++i) {
      for (std::size_t j = i + 1; j < time_events.size(); ++j) {
        if (shares(*time_events[i], *time_events[j])) group[root(j)] = root(i);
      }
    }
    double p = 1.0;
    for (std::size_t g = 0; g < time_events.size(); ++g) {
      if (root(g) != g) continue;
      std::vector<const detail::Event*> members;
      std::vector<std::size_t> vars;
      for (std::size_t i = 0; i < time_events.size(); ++i) {
        if (root(i) != g) continue;
        members.push_back(time_events[i]);
        for (const std::string* name : {&time_events[i]->a, &time_events[i]->b}) {
          if (name->empty()) continue;
          const std::size_t r = bound_.at(*name).robot;
          if (std::find(vars.begin(), vars.end(), r) == vars.end()) vars.push_back(r);
        }
      }
      if (members.size() == 1) {  // one event: its closed form
        p *= event_probability(b, *members.front());
        continue;
      }
      if (vars.size() > 3) {
        double sum = 0.0;
        for (const detail::Event* e : members) sum += event_probability(b, *e);
        p *= std::max(0.0, sum - static_cast<double>(members.size() - 1));
        continue;
      }
      std::vector<double> value(vars.size(), 0.0);
      p *= integrate(b, members, vars, value, 0);
    }
    return p;
  }

  /// Integrates out vars[k..] given value[0..k).
  double integrate(const Branch& b, const std::vector<const detail::Event*>& members, const std::vector<std::size_t>& vars,
                   std::vector<double>& value, std::size_t k) const {
    const auto index_of = [&](const std::string& name) {
      const std::size_t r = bound_.at(name).robot;
      return static_cast<std::size_t>(std::find(vars.begin(), vars.end(), r) - vars.begin());
    };
    const Mixture1& t = b.robots[vars[k]].finish_time_s;
    if (k + 1 == vars.size()) {
      // The last variable: every event is a bound on it, or already decided.
      double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
      for (const detail::Event* e : members) {
        const std::size_t ia = index_of(e->a);
        const bool less = detail::is_less(e->op);
        if (e->kind == detail::Event::Kind::time_bound) {
          // a + offset OP value: a bound on a (the last variable).
          (less ? hi : lo) = less ? std::min(hi, e->value - e->offset) : std::max(lo, e->value - e->offset);
          continue;
        }
        const std::size_t ib = index_of(e->b);
        if (ia == k && ib == k) return 0.0;  // not produced by the parser (a variable compared with itself)
        if (ia == k) {  // a + offset OP value[b]
          const double bound = value[ib] - e->offset;
          if (less) hi = std::min(hi, bound); else lo = std::max(lo, bound);
        } else if (ib == k) {  // value[a] + offset OP b
          const double bound = value[ia] + e->offset;
          if (less) lo = std::max(lo, bound); else hi = std::min(hi, bound);
        } else {
          const bool holds = less ? value[ia] + e->offset < value[ib] : value[ia] + e->offset > value[ib];
          if (!holds) return 0.0;
        }
      }
      if (!(lo < hi)) return 0.0;
      return std::max(0.0, (std::isfinite(hi) ? t.cdf(hi) : 1.0) - (std::isfinite(lo) ? t.cdf(lo) : 0.0));
    }
    // Integrate this variable out: per component, cells of exact mass over
    // mean +- 8 sd, each evaluated at its conditional mean.
    const std::size_t cells = vars.size() == 2 ? 400 : 48;
    double total = 0.0;
    for (const Component1& c : t.components) {
      if (!(c.weight > 0.0)) continue;
      if (!(c.var > 0.0)) {
        value[k] = c.mean;
        total += c.weight * integrate(b, members, vars, value, k + 1);
        continue;
      }
      const double sd = std::sqrt(c.var);
      constexpr double kSpan = 8.0;
      for (std::size_t i = 0; i < cells; ++i) {
        const double z0 = -kSpan + 2.0 * kSpan * static_cast<double>(i) / static_cast<double>(cells);
        const double z1 = -kSpan + 2.0 * kSpan * static_cast<double>(i + 1) / static_cast<double>(cells);
        const double mass = normal_cdf(z1) - normal_cdf(z0);
        if (!(mass > 0.0)) continue;
        const double z = (normal_pdf(z0) - normal_pdf(z1)) / mass;  // the cell's conditional mean
        value[k] = c.mean + sd * z;
        total += c.weight * mass * integrate(b, members, vars, value, k + 1);
      }
    }
    return total;
  }

  /// P(every event) in one branch when the events ask about one robot's
  /// finish time (bounds only) and its distance to one point, and that
  /// robot's final points carry time scores (engine/time_position.hpp, issue
  /// 13 item 7): the two together, through the same copula as vipars verify's
  /// joint; the other events as before. nullopt when that is not the case
  /// (no scores, an ordering or a second position event on the robot).
  std::optional<double> coupled_probability(const Branch& b, const std::vector<detail::Event>& events) const {
    const detail::Event* place = nullptr;
    std::size_t r = 0;
    for (const detail::Event& e : events) {
      if (e.kind != detail::Event::Kind::distance_to_point) continue;
      if (!engine::has_time_scores(robot(b, e.a))) continue;
      if (place != nullptr) return std::nullopt;  // two candidates: keep the plain product
      place = &e;
      r = bound_.at(e.a).robot;
    }
    if (place == nullptr) return std::nullopt;
    const auto on_r = [&](const std::string& name) { return !name.empty() && bound_.at(name).robot == r; };
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    bool timed = false;
    std::vector<detail::Event> rest_time, rest_other;
    for (const detail::Event& e : events) {
      if (&e == place) continue;
      if (e.kind == detail::Event::Kind::time_bound && on_r(e.a)) {
        timed = true;
        const double bound = e.value - e.offset;
        if (detail::is_less(e.op)) hi = std::min(hi, bound); else lo = std::max(lo, bound);
      } else if (on_r(e.a) || on_r(e.b)) {
        return std::nullopt;  // an ordering or another position of the same robot
      } else if (is_time(e)) {
        rest_time.push_back(e);
      } else {
        rest_other.push_back(e);
      }
    }
    if (!timed) return std::nullopt;
    const RobotOutcome& ro = b.robots[r];
    const double p_hi = std::isfinite(hi) ? ro.finish_time_s.cdf(hi) : 1.0;
    const double p_lo = std::isfinite(lo) ? ro.finish_time_s.cdf(lo) : 0.0;
    double coupled = 0.0;
    if (hi > lo && p_hi > p_lo) {
      // P(t <= bound | component k) at both ends of the interval.
      const std::size_t n = ro.final_components.size();
      const engine::TimeScores scores = engine::time_scores_of(ro);
      const std::vector<double> upper = engine::time_given_components(scores, p_hi);
      const std::vector<double> lower = engine::time_given_components(scores, p_lo);
      const bool less = detail::is_less(place->op);
      double p_place = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        const double inside = probability_within(ro.final_components[k], Eigen::Vector2d(place->x, place->y), place->value);
        const double event = less ? inside : 1.0 - inside;
        p_place += component_weight(ro, k) * event;
        coupled += component_weight(ro, k) * std::max(0.0, upper[k] - lower[k]) * event;
      }
      const double p_time = p_hi - p_lo;
      coupled = std::clamp(coupled, std::max(0.0, p_time + p_place - 1.0), std::min(p_time, p_place));
    }
    double p = coupled * joint_time_probability(b, rest_time);
    for (const detail::Event& e : rest_other) p *= event_probability(b, e);
    return p;
  }

  double probability(const std::vector<detail::Event>& events) const {
    double total = 0.0;
    for (const Branch& b : o_.branches) {
      if (b.robots.size() != m_.robots.size()) continue;
      // A robot that never gets to its At in this branch cannot match the network.
      bool finished = true;
      for (const std::size_t r : robots_) finished = finished && b.robots[r].finished;
      if (!finished) continue;
      // Time events that share a robot's finish time are dependent (t1 <= 200
      // and t1 < t3 both ask about t1): computed jointly. Events on
      // different robots' times, and position events, are independent
      // within a branch as the model carries them.
      // A robot's finish time and its final position, when its final
      // points carry time scores, together (coupled_probability).
      double p = 0.0;
      if (const std::optional<double> coupled = coupled_probability(b, events)) {
        p = *coupled;
      } else {
        p = joint_time_probability(b, events);
        for (const detail::Event& e : events) {
          if (!is_time(e)) p *= event_probability(b, e);
        }
      }
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
    const double lost = o_.pruned_mass + o_.blocked_mass + o_.loop_cutoff_mass + o_.work_cutoff_mass;
    if (lost > 0.0) {
      explanation += "; pruned and blocked mass " + format_probability(lost) + " counts as failure";
    }
    v.explanation = explanation;
    return v;
  }

  const Criterion& c_;
  const mission::Mission& m_;
  const SystemOutcome& o_;
  double separation_step_m_ = 0.0;
  std::vector<std::size_t> robots_;
  std::map<std::string, Symbol> symbols_;
  std::map<std::string, Symbol> bound_;
};

}  // namespace

Result<CriterionVerdict> evaluate_criterion(const Criterion& criterion, const mission::Mission& mission,
                                            const SystemOutcome& outcome, double default_required_probability,
                                            double separation_step_m) {
  return Evaluator(criterion, mission, outcome, separation_step_m).run(default_required_probability);
}

}  // namespace p3at::verifier
