#include "p3at/verifier/pars/expr.hpp"

#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

#include "p3at/common/number_format.hpp"

namespace p3at::verifier::pars {

const char* to_string(CompareOp op) {
  switch (op) {
    case CompareOp::equal: return "=";
    case CompareOp::not_equal: return "!=";
    case CompareOp::less: return "<";
    case CompareOp::less_equal: return "<=";
    case CompareOp::greater: return ">";
    case CompareOp::greater_equal: return ">=";
  }
  return "?";
}

CompareOp swapped(CompareOp op) {
  switch (op) {
    case CompareOp::equal: return CompareOp::equal;
    case CompareOp::not_equal: return CompareOp::not_equal;
    case CompareOp::less: return CompareOp::greater;
    case CompareOp::less_equal: return CompareOp::greater_equal;
    case CompareOp::greater: return CompareOp::less;
    case CompareOp::greater_equal: return CompareOp::less_equal;
  }
  return op;
}

Expr number(double value) {
  Expr e;
  e.kind = ExprKind::number;
  e.number = value;
  return e;
}

Expr name(std::string name) {
  Expr e;
  e.kind = ExprKind::name;
  e.name = std::move(name);
  return e;
}

Expr tuple(std::vector<Expr> elements) {
  Expr e;
  e.kind = ExprKind::tuple;
  e.args = std::move(elements);
  return e;
}

Expr point(double x, double y) { return tuple({number(x), number(y)}); }

Expr call(std::string function, std::vector<Expr> args) {
  Expr e;
  e.kind = ExprKind::call;
  e.name = std::move(function);
  e.args = std::move(args);
  return e;
}

Expr negate(Expr operand) {
  Expr e;
  e.kind = ExprKind::negate;
  e.args.push_back(std::move(operand));
  return e;
}

Expr binary(ExprKind kind, Expr left, Expr right) {
  Expr e;
  e.kind = kind;
  e.args.push_back(std::move(left));
  e.args.push_back(std::move(right));
  return e;
}

Expr add(Expr left, Expr right) { return binary(ExprKind::add, std::move(left), std::move(right)); }
Expr subtract(Expr left, Expr right) { return binary(ExprKind::subtract, std::move(left), std::move(right)); }
Expr multiply(Expr left, Expr right) { return binary(ExprKind::multiply, std::move(left), std::move(right)); }
Expr divide(Expr left, Expr right) { return binary(ExprKind::divide, std::move(left), std::move(right)); }

Expr norm(Expr operand) {
  Expr e;
  e.kind = ExprKind::norm;
  e.args.push_back(std::move(operand));
  return e;
}

Expr compare(CompareOp op, Expr left, Expr right) {
  Expr e = binary(ExprKind::add, std::move(left), std::move(right));
  e.kind = ExprKind::compare;
  e.op = op;
  return e;
}

std::string format_number(double value) { return format_shortest(value); }

namespace {

// Binding strength, loosest first; atoms bind tightest.
int precedence(const Expr& e) {
  switch (e.kind) {
    case ExprKind::compare: return 0;
    case ExprKind::add:
    case ExprKind::subtract: return 1;
    case ExprKind::multiply:
    case ExprKind::divide: return 2;
    case ExprKind::negate: return 3;
    case ExprKind::number:
    case ExprKind::name:
    case ExprKind::tuple:
    case ExprKind::call:
    case ExprKind::norm: return 4;
  }
  return 4;
}

const char* binary_symbol(ExprKind kind) {
  switch (kind) {
    case ExprKind::add: return " + ";
    case ExprKind::subtract: return " - ";
    case ExprKind::multiply: return " * ";
    case ExprKind::divide: return " / ";
    case ExprKind::number:
    case ExprKind::name:
    case ExprKind::tuple:
    case ExprKind::call:
    case ExprKind::negate:
    case ExprKind::norm:
    case ExprKind::compare: break;
  }
  return " ? ";
}

void print(const Expr& e, std::string& out);

void print_parenthesised(const Expr& e, bool parens, std::string& out) {
  if (parens) out += '(';
  print(e, out);
  if (parens) out += ')';
}

// Elements inside parentheses (tuples, call arguments) may be comparisons.
void print_list(const std::vector<Expr>& items, std::string& out) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += ", ";
    print(items[i], out);
  }
}

void print(const Expr& e, std::string& out) {
  switch (e.kind) {
    case ExprKind::number: out += format_shortest(e.number); return;
    case ExprKind::name: out += e.name; return;
    case ExprKind::tuple:
      out += '(';
      print_list(e.args, out);
      if (e.args.size() == 1) out += ',';  // a 1-tuple, not a parenthesised expression
      out += ')';
      return;
    case ExprKind::call:
      out += e.name;
      out += '(';
      print_list(e.args, out);
      out += ')';
      return;
    case ExprKind::negate: {
      out += '-';
      if (e.args.empty()) return;
      const Expr& operand = e.args[0];
      // -(3) keeps a negated literal apart from the literal -3.
      print_parenthesised(operand, operand.kind == ExprKind::number || precedence(operand) < 3, out);
      return;
    }
    case ExprKind::norm:
      out += '|';
      if (!e.args.empty()) print_parenthesised(e.args[0], e.args[0].kind == ExprKind::compare, out);
      out += '|';
      return;
    case ExprKind::add:
    case ExprKind::subtract:
    case ExprKind::multiply:
    case ExprKind::divide:
    case ExprKind::compare: {
      if (e.args.size() != 2) return;
      const int p = precedence(e);
      // Left-associative: a left operand of the same strength needs no parentheses,
      // a right one does (a - (b - c)); comparisons never chain.
      const bool left_parens = e.kind == ExprKind::compare ? precedence(e.args[0]) == 0 : precedence(e.args[0]) < p;
      print_parenthesised(e.args[0], left_parens, out);
      if (e.kind == ExprKind::compare) {
        out += ' ';
        out += to_string(e.op);
        out += ' ';
      } else {
        out += binary_symbol(e.kind);
      }
      print_parenthesised(e.args[1], precedence(e.args[1]) <= p, out);
      return;
    }
  }
}

std::optional<double> finite(double v) {
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

std::string to_string(const Expr& expr) {
  std::string out;
  print(expr, out);
  return out;
}

std::optional<double> constant_value(const Expr& e) {
  switch (e.kind) {
    case ExprKind::number: return finite(e.number);
    case ExprKind::negate: {
      if (e.args.size() != 1) return std::nullopt;
      const auto v = constant_value(e.args[0]);
      if (!v) return std::nullopt;
      return -*v;
    }
    case ExprKind::add:
    case ExprKind::subtract:
    case ExprKind::multiply:
    case ExprKind::divide: {
      if (e.args.size() != 2) return std::nullopt;
      const auto a = constant_value(e.args[0]);
      const auto b = constant_value(e.args[1]);
      if (!a || !b) return std::nullopt;
      if (e.kind == ExprKind::add) return finite(*a + *b);
      if (e.kind == ExprKind::subtract) return finite(*a - *b);
      if (e.kind == ExprKind::multiply) return finite(*a * *b);
      return finite(*a / *b);
    }
    case ExprKind::name:
    case ExprKind::tuple:
    case ExprKind::call:
    case ExprKind::norm:
    case ExprKind::compare: return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::pair<double, double>> constant_point(const Expr& e) {
  if (e.kind != ExprKind::tuple || e.args.size() != 2) return std::nullopt;
  const auto x = constant_value(e.args[0]);
  const auto y = constant_value(e.args[1]);
  if (!x || !y) return std::nullopt;
  return std::make_pair(*x, *y);
}

Expr substitute(const Expr& e, const std::function<std::optional<Expr>(const std::string&)>& lookup) {
  if (e.kind == ExprKind::name) {
    if (auto replacement = lookup(e.name)) return *replacement;
    return e;
  }
  Expr out = e;
  for (Expr& arg : out.args) arg = substitute(arg, lookup);
  return out;
}

namespace {
void collect_names(const Expr& e, std::vector<std::string>& names) {
  if (e.kind == ExprKind::name) {
    for (const auto& n : names) {
      if (n == e.name) return;
    }
    names.push_back(e.name);
    return;
  }
  for (const Expr& arg : e.args) collect_names(arg, names);
}
}  // namespace

std::vector<std::string> names_in(const Expr& expr) {
  std::vector<std::string> names;
  collect_names(expr, names);
  return names;
}

}  // namespace p3at::verifier::pars
