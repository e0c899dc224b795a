#include "p3at/verifier/pars/abort_condition.hpp"

#include <utility>

namespace p3at::verifier::pars {

namespace {

struct Comparison {
  std::string_view name;
  CompareOp op;
};
constexpr Comparison kComparisons[] = {
    {"EQ", CompareOp::equal},          {"NEQ", CompareOp::not_equal}, {"LT", CompareOp::less},
    {"GT", CompareOp::greater},        {"LEQ", CompareOp::less_equal}, {"GEQ", CompareOp::greater_equal},
};

bool is_trigger_name(std::string_view n) {
  return n == "Is_at_goal" || n == "Has_turned" || n == "Got_message" || n == "Message_sent";
}

Condition never() { return Condition{}; }

Condition any_of(std::vector<Condition> parts) {
  std::vector<Condition> kept;
  for (Condition& c : parts) {
    if (c.kind == Condition::Kind::never) continue;
    if (c.kind == Condition::Kind::any) {
      for (Condition& inner : c.parts) kept.push_back(std::move(inner));
    } else {
      kept.push_back(std::move(c));
    }
  }
  if (kept.empty()) return never();
  if (kept.size() == 1) return std::move(kept.front());
  Condition c;
  c.kind = Condition::Kind::any;
  c.parts = std::move(kept);
  return c;
}

// Sequences are n-ary: a ; (b ; c) is kept as one list a ; b ; c.
Condition then(Condition first, Condition second) {
  if (second.kind == Condition::Kind::never) return first;
  Condition c;
  c.kind = Condition::Kind::then;
  for (Condition* side : {&first, &second}) {
    if (side->kind == Condition::Kind::then) {
      for (Condition& inner : side->parts) c.parts.push_back(std::move(inner));
    } else {
      c.parts.push_back(std::move(*side));
    }
  }
  return c;
}

Condition omega(const Term& t, const Term* recursion) {
  if (t.is_process()) {
    if (&t == recursion) return never();
    auto expr = condition_of(t);
    if (!expr) return never();
    Condition c;
    c.kind = Condition::Kind::atom;
    c.process = t;
    c.expr = std::move(*expr);
    return c;
  }
  switch (t.op) {
    case Op::parallel:
    case Op::disabling: {
      std::vector<Condition> parts;
      for (const Term& part : t.parts) parts.push_back(omega(part, recursion));
      return any_of(std::move(parts));
    }
    case Op::sequence: {
      // Ω(P1 ; P2 ; ... ; Pn) = Ω(P1) ; (Ω(P2) ; (... ; Ω(Pn))), folded from the right
      // so that a tail that never aborts drops out.
      Condition c = omega(t.parts.back(), recursion);
      for (std::size_t i = t.parts.size() - 1; i-- > 0;) c = then(omega(t.parts[i], recursion), std::move(c));
      return c;
    }
  }
  return never();
}

void print(const Condition& c, int parent_strength, std::string& out) {
  // "or" is 1, ";" is 2; atoms never need parentheses (their comparison is
  // the loosest thing inside them, and they stand alone).
  switch (c.kind) {
    case Condition::Kind::never: out += "never"; return;
    case Condition::Kind::atom: out += to_string(c.expr); return;
    case Condition::Kind::any:
    case Condition::Kind::then: {
      const int strength = c.kind == Condition::Kind::any ? 1 : 2;
      const bool parens = strength <= parent_strength;
      if (parens) out += '(';
      for (std::size_t i = 0; i < c.parts.size(); ++i) {
        if (i > 0) out += c.kind == Condition::Kind::any ? " or " : " ; ";
        print(c.parts[i], strength, out);
      }
      if (parens) out += ')';
      return;
    }
  }
}

}  // namespace

bool is_condition_process(const Term& p) {
  if (!p.is_process()) return false;
  for (const Comparison& c : kComparisons) {
    if (p.name == c.name) return true;
  }
  return is_trigger_name(p.name);
}

std::optional<Expr> condition_of(const Term& p) {
  if (!p.is_process()) return std::nullopt;
  for (const Comparison& c : kComparisons) {
    if (p.name == c.name) {
      if (p.params.size() != 2) return std::nullopt;
      return compare(c.op, p.params[0], p.params[1]);
    }
  }
  if (p.name == "Is_at_goal") {
    if (p.params.size() != 2 || p.in_ports.size() != 1) return std::nullopt;
    return compare(CompareOp::less_equal, norm(subtract(name(p.in_ports[0]), p.params[0])), p.params[1]);
  }
  if (p.name == "Has_turned") {
    if (p.params.size() != 2 || p.in_ports.size() != 1) return std::nullopt;
    Expr angle = p.params[0];
    // Has_turned<90, 0> reads "turned(d) >= 90"; a non-zero offset is subtracted.
    const auto offset = constant_value(p.params[1]);
    const auto value = constant_value(p.params[0]);
    if (offset && value) {
      angle = number(*value - *offset);
    } else if (!offset || *offset != 0.0) {
      angle = subtract(p.params[0], p.params[1]);
    }
    return compare(CompareOp::greater_equal, call("turned", {name(p.in_ports[0])}), angle);
  }
  if (p.name == "Got_message" || p.name == "Message_sent") {
    if (p.params.size() != 1 || p.in_ports.size() != 1) return std::nullopt;
    return call(p.name == "Got_message" ? "received" : "acked", {name(p.in_ports[0])});
  }
  return std::nullopt;
}

Condition abort_condition(const Term& term) { return omega(term, nullptr); }

Condition abort_condition(const Definition& definition) { return omega(definition.body, tail_call(definition)); }

std::string to_string(const Condition& condition) {
  std::string out;
  print(condition, 0, out);
  return out;
}

}  // namespace p3at::verifier::pars
