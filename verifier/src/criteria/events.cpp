#include "criteria/events.hpp"

#include <optional>

#include "p3at/verifier/pars/printer.hpp"

namespace p3at::verifier::detail {

namespace {

using pars::Expr;
using pars::ExprKind;

// var + constant (or just a constant) in a time comparison.
struct Linear {
  std::optional<std::string> var;
  double constant = 0.0;
};

std::optional<Linear> linear(const Expr& e) {
  if (const auto c = pars::constant_value(e)) return Linear{std::nullopt, *c};
  if (e.kind == ExprKind::name) return Linear{e.name, 0.0};
  if ((e.kind == ExprKind::add || e.kind == ExprKind::subtract) && e.args.size() == 2) {
    const auto l = linear(e.args[0]);
    const auto r = linear(e.args[1]);
    if (!l || !r || (l->var && r->var)) return std::nullopt;
    if (e.kind == ExprKind::subtract && r->var) return std::nullopt;  // c - t: t with a negative sign
    return Linear{l->var ? l->var : r->var,
                  e.kind == ExprKind::add ? l->constant + r->constant : l->constant - r->constant};
  }
  return std::nullopt;
}

// |X - Y| with X, Y positions or constant points.
struct Distance {
  std::optional<std::string> a, b;
  std::optional<std::pair<double, double>> pa, pb;
};

std::optional<Distance> distance(const Expr& e) {
  if (e.kind != ExprKind::norm || e.args.size() != 1) return std::nullopt;
  const Expr& d = e.args[0];
  if (d.kind != ExprKind::subtract || d.args.size() != 2) return std::nullopt;
  Distance out;
  const auto side = [](const Expr& x, std::optional<std::string>& var, std::optional<std::pair<double, double>>& p) {
    if (x.kind == ExprKind::name) {
      var = x.name;
      return true;
    }
    p = pars::constant_point(x);
    return p.has_value();
  };
  if (!side(d.args[0], out.a, out.pa) || !side(d.args[1], out.b, out.pb)) return std::nullopt;
  return out;
}

const char* kind_name(VariableKind k) { return k == VariableKind::time ? "a time" : "a position"; }

}  // namespace

bool is_less(pars::CompareOp op) { return op == pars::CompareOp::less || op == pars::CompareOp::less_equal; }

bool classify(const Comparison& c, const VariableKinds& kinds, std::vector<Event>& events, std::string& problem) {
  events.clear();
  if (c.op == pars::CompareOp::equal || c.op == pars::CompareOp::not_equal) {
    problem = "compare with <, <=, > or >= (for continuous variables, '" + std::string(pars::to_string(c.op)) +
              "' has probability " + (c.op == pars::CompareOp::equal ? "0" : "1") + ")";
    return false;
  }
  // Every name must be one of the network's variables.
  for (const Expr* side : {&c.right}) {
    for (const auto& n : pars::names_in(*side)) {
      if (kinds.count(n) == 0) {
        problem = "unknown variable '" + n + "' (not a parameter of the network's Delay or At processes)";
        return false;
      }
    }
  }
  for (const Expr& l : c.left) {
    for (const auto& n : pars::names_in(l)) {
      if (kinds.count(n) == 0) {
        problem = "unknown variable '" + n + "' (not a parameter of the network's Delay or At processes)";
        return false;
      }
    }
  }
  if (c.left.size() > 1) {
    // t1, t3 <= 200: the same comparison for each variable.
    for (const Expr& l : c.left) {
      if (l.kind != ExprKind::name) {
        problem = "a list before a comparison must be variables only, got '" + pars::to_string(l) + "'";
        return false;
      }
      std::vector<Event> one;
      if (!classify(Comparison{{l}, c.op, c.right, c.line, c.column}, kinds, one, problem)) return false;
      events.insert(events.end(), one.begin(), one.end());
    }
    return true;
  }
  if (c.left.empty()) {
    problem = "empty comparison";
    return false;
  }
  const Expr& left = c.left.front();
  // Distances: one side |X - Y|, the other a constant.
  const auto dl = distance(left);
  const auto dr = distance(c.right);
  if (dl || dr) {
    const Distance& d = dl ? *dl : *dr;
    const auto limit = pars::constant_value(dl ? c.right : left);
    const pars::CompareOp op = dl ? c.op : pars::swapped(c.op);
    if (!limit) {
      problem = "compare a distance with a constant, got '" + pars::to_string(dl ? c.right : left) + "'";
      return false;
    }
    if (*limit < 0.0) {
      problem = "a distance is never negative: compare it with a length >= 0, got " + pars::format_number(*limit);
      return false;
    }
    for (const auto* var : {&d.a, &d.b}) {
      if (*var && kinds.at(**var) != VariableKind::position) {
        problem = "'" + **var + "' is " + kind_name(kinds.at(**var)) + ", not a position (At's second parameter)";
        return false;
      }
    }
    Event e;
    e.op = op;
    e.value = *limit;
    if (d.a && d.b) {
      if (*d.a == *d.b) {
        problem = "|" + *d.a + " - " + *d.b + "| is always 0";
        return false;
      }
      e.kind = Event::Kind::distance_between;
      e.a = *d.a;
      e.b = *d.b;
    } else if (d.a || d.b) {
      e.kind = Event::Kind::distance_to_point;
      e.a = d.a ? *d.a : *d.b;
      const auto& p = d.a ? *d.pb : *d.pa;
      e.x = p.first;
      e.y = p.second;
    } else {
      problem = "the distance between two constant points is not a constraint on the system";
      return false;
    }
    events.push_back(e);
    return true;
  }
  // Times: var + constant on either side (or both).
  const auto ll = linear(left);
  const auto lr = linear(c.right);
  if (!ll || !lr) {
    problem = "expected a time comparison (t <= 200, t1 + 5 < t3) or a distance (|p - (x, y)| < r, |p - q| > d), got '" +
              pars::to_string(!ll ? left : c.right) + "'";
    return false;
  }
  for (const auto* var : {&ll->var, &lr->var}) {
    if (*var && kinds.at(**var) != VariableKind::time) {
      problem = "'" + **var + "' is " + kind_name(kinds.at(**var)) +
                ": constrain its distance, as in |" + **var + " - (x, y)| < r";
      return false;
    }
  }
  Event e;
  if (ll->var && lr->var) {
    if (*ll->var == *lr->var) {
      problem = "'" + *ll->var + "' is compared with itself";
      return false;
    }
    e.kind = Event::Kind::time_order;
    e.a = *ll->var;
    e.b = *lr->var;
    e.offset = ll->constant - lr->constant;
    e.op = c.op;
  } else if (ll->var || lr->var) {
    e.kind = Event::Kind::time_bound;
    e.a = ll->var ? *ll->var : *lr->var;
    e.offset = ll->var ? ll->constant : lr->constant;
    e.value = ll->var ? lr->constant : ll->constant;
    e.op = ll->var ? c.op : pars::swapped(c.op);
  } else {
    problem = "the comparison involves no variable";
    return false;
  }
  events.push_back(e);
  return true;
}

}  // namespace p3at::verifier::detail
