#pragma once
/// Expressions of PARS (docs/pars.md): a process's parameters (the paper's
/// subscripts), the values its port operations write, the conditions of
/// condition processes and the constraints of criteria.
///
/// Plain value trees with operator==; the printer writes them so that the
/// parser reads back an equal tree (parse_expr(to_string(e)) == e).

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace p3at::verifier::pars {

enum class ExprKind {
  number,    ///< a finite double
  name,      ///< a variable, constant or port name
  tuple,     ///< (a, b, ...): a point, a pose, a list of walls
  call,      ///< f(a, b, ...): a named function of its arguments, e.g. z(u, t)
  negate,    ///< -a
  add,       ///< a + b
  subtract,  ///< a - b
  multiply,  ///< a * b
  divide,    ///< a / b
  norm,      ///< |a|: Euclidean length
  compare,   ///< a OP b (conditions and constraints only; never a parameter)
};

enum class CompareOp { equal, not_equal, less, less_equal, greater, greater_equal };

/// The spelling of a comparison: "=", "!=", "<", "<=", ">", ">=".
const char* to_string(CompareOp op);
/// The comparison with its operands swapped: a < b  <=>  b > a.
CompareOp swapped(CompareOp op);

struct Expr {
  ExprKind kind = ExprKind::number;
  double number = 0.0;                   ///< kind number
  std::string name;                      ///< kind name; the function of kind call
  CompareOp op = CompareOp::equal;       ///< kind compare
  std::vector<Expr> args;                ///< elements, arguments or operands (1 or 2)

  bool operator==(const Expr&) const = default;
};

// Builders (the translator and the tests build terms with these).
Expr number(double value);
Expr name(std::string name);
Expr tuple(std::vector<Expr> elements);
Expr point(double x, double y);
Expr call(std::string function, std::vector<Expr> args);
Expr negate(Expr operand);
Expr binary(ExprKind kind, Expr left, Expr right);  ///< kind is add, subtract, multiply or divide
Expr add(Expr left, Expr right);
Expr subtract(Expr left, Expr right);
Expr multiply(Expr left, Expr right);
Expr divide(Expr left, Expr right);
Expr norm(Expr operand);
Expr compare(CompareOp op, Expr left, Expr right);

/// One line, minimal parentheses, numbers in their shortest exact form.
std::string to_string(const Expr& expr);
/// Numbers as printed in PARS text: the shortest form that reads back exactly.
std::string format_number(double value);

/// The value of an expression made only of numbers, + - * / and unary minus;
/// nullopt if it involves anything else or is not finite.
std::optional<double> constant_value(const Expr& expr);
/// (x, y) if `expr` is a tuple of two constant expressions.
std::optional<std::pair<double, double>> constant_point(const Expr& expr);

/// Replaces every name for which `lookup` returns a value (function names of
/// calls are not names and are kept).
Expr substitute(const Expr& expr, const std::function<std::optional<Expr>(const std::string&)>& lookup);
/// The names an expression mentions, in first-use order, without duplicates.
std::vector<std::string> names_in(const Expr& expr);

}  // namespace p3at::verifier::pars
