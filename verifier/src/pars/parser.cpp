#include "p3at/verifier/pars/parser.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>
#include <utility>

#include "pars/parser_impl.hpp"

namespace p3at::verifier::pars {

namespace detail {
namespace {

bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }

// A character from the input as a readable, one-line quote.
std::string quote_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "'\\x%02X'", static_cast<unsigned>(u));
  return buffer;
}

std::string cut(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, 48)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out += c;
    } else {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\x%02X", static_cast<unsigned>(u));
      out += buffer;
    }
  }
  if (text.size() > 48) out += "...";
  return out;
}

}  // namespace

Parser::Parser(std::string_view text, std::string source) : source_(std::move(source)) {
  int line = 1;
  int column = 1;
  bool line_has_token = false;
  std::size_t i = 0;
  const auto fail_at = [&](const std::string& detail) { throw ParseError(source_, line, column, detail); };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      column = 1;
      line_has_token = false;
      ++i;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      ++column;
      ++i;
      continue;
    }
    if (c == '#' && !line_has_token) {
      // A '#' first on its line starts a comment; anywhere else it is the operator.
      std::size_t j = i + 1;
      while (j < text.size() && text[j] != '\n') ++j;
      std::string_view body = text.substr(i + 1, j - i - 1);
      if (!body.empty() && body.front() == ' ') body.remove_prefix(1);
      // Every trailing CR (a CRLF file, or stray ones): stripping only one left
      // "x\r" from "x\r\r", which prints as "# x\r" and reads back as "x"
      // (found by fuzz_pars_parser in a long run; the input is in its corpus).
      while (!body.empty() && body.back() == '\r') body.remove_suffix(1);
      comments_.push_back(Comment{line, std::string(body)});
      column += static_cast<int>(j - i);
      i = j;
      continue;
    }
    Token token;
    token.line = line;
    token.column = column;
    token.first_on_line = !line_has_token;
    std::size_t length = 1;
    if (is_name_start(c)) {
      // Names may contain '.' between name characters (robot1.bound_ow2).
      while (i + length < text.size() &&
             (is_name_char(text[i + length]) ||
              (text[i + length] == '.' && i + length + 1 < text.size() && is_name_char(text[i + length + 1])))) {
        ++length;
      }
      token.kind = Tok::name;
    } else if (is_digit(c)) {
      while (i + length < text.size() && is_digit(text[i + length])) ++length;
      if (i + length < text.size() && text[i + length] == '.') {
        ++length;
        if (i + length >= text.size() || !is_digit(text[i + length])) {
          column += static_cast<int>(length);
          fail_at("expected a digit after the decimal point");
        }
        while (i + length < text.size() && is_digit(text[i + length])) ++length;
      }
      if (i + length < text.size() && (text[i + length] == 'e' || text[i + length] == 'E')) {
        std::size_t k = length + 1;
        if (i + k < text.size() && (text[i + k] == '+' || text[i + k] == '-')) ++k;
        if (i + k < text.size() && is_digit(text[i + k])) {
          while (i + k < text.size() && is_digit(text[i + k])) ++k;
          length = k;
        }
      }
      token.kind = Tok::number;
      const char* first = text.data() + i;
      const auto [ptr, ec] = std::from_chars(first, first + length, token.number);
      if (ec != std::errc() || ptr != first + length || !std::isfinite(token.number)) {
        fail_at("number out of range: " + cut(text.substr(i, length)));
      }
    } else {
      const char d = i + 1 < text.size() ? text[i + 1] : '\0';
      switch (c) {
        case '<': token.kind = d == '=' ? Tok::less_equal : Tok::less; break;
        case '>': token.kind = d == '=' ? Tok::greater_equal : Tok::greater; break;
        case '=': token.kind = Tok::equal; break;
        case '!':
          if (d != '=') fail_at("unexpected character '!' (did you mean '!='?)");
          token.kind = Tok::not_equal;
          break;
        case '(': token.kind = Tok::lparen; break;
        case ')': token.kind = Tok::rparen; break;
        case ',': token.kind = Tok::comma; break;
        case ';': token.kind = Tok::semicolon; break;
        case '|': token.kind = Tok::bar; break;
        case '#': token.kind = Tok::hash; break;
        case '+': token.kind = Tok::plus; break;
        case '-': token.kind = d == '>' ? Tok::arrow : Tok::minus; break;
        case '*': token.kind = Tok::star; break;
        case '/': token.kind = Tok::slash; break;
        default: fail_at("unexpected character " + quote_char(c));
      }
      if ((c == '<' || c == '>' || c == '!') && d == '=') length = 2;
      if (c == '=' && d == '=') length = 2;  // '==' reads as '='
      if (c == '-' && d == '>') length = 2;
    }
    token.text = text.substr(i, length);
    tokens_.push_back(token);
    line_has_token = true;
    column += static_cast<int>(length);
    i += length;
  }
  Token end;
  end.kind = Tok::end;
  end.line = line;
  end.column = column;
  end.first_on_line = !line_has_token;
  tokens_.push_back(end);
}

const Token& Parser::peek(std::size_t ahead) const {
  const std::size_t index = pos_ + ahead;
  return index < tokens_.size() ? tokens_[index] : tokens_.back();
}

const Token& Parser::next() {
  const Token& token = peek();
  if (pos_ + 1 < tokens_.size()) ++pos_;
  return token;
}

bool Parser::accept(Tok kind) {
  if (!at(kind)) return false;
  next();
  return true;
}

const Token& Parser::expect(Tok kind, const std::string& what) {
  if (!at(kind)) fail(peek(), "expected " + what + ", got " + describe(peek()));
  return next();
}

void Parser::fail(const Token& at, const std::string& detail) const {
  throw ParseError(source_, at.line, at.column, detail);
}

std::string Parser::describe(const Token& token) {
  if (token.kind == Tok::end) return "the end of the input";
  return "'" + cut(token.text) + "'";
}

void Parser::check_depth(int depth, const Token& at) const {
  if (depth > kMaxNesting) fail(at, "nested too deeply (more than " + std::to_string(kMaxNesting) + " levels)");
}

// ------------------------------------------------------------------ terms

namespace {
Tok token_of(Op op) {
  switch (op) {
    case Op::disabling: return Tok::hash;
    case Op::parallel: return Tok::bar;
    case Op::sequence: return Tok::semicolon;
  }
  return Tok::semicolon;
}
}  // namespace

Term Parser::term() { return term_at(Op::disabling, 0); }

// One precedence level: parts of the tighter level joined by this level's operator.
Term Parser::term_at(Op level, int nesting) {
  const auto part = [&]() {
    if (level == Op::sequence) return primary(nesting);
    return term_at(level == Op::disabling ? Op::parallel : Op::sequence, nesting);
  };
  std::vector<Term> parts;
  parts.push_back(part());
  while (accept(token_of(level))) parts.push_back(part());
  return compose(level, std::move(parts));
}

Term Parser::primary(int nesting) {
  if (at(Tok::lparen)) {
    const Token& open = next();
    check_depth(nesting + 1, open);
    Term inner = term_at(Op::disabling, nesting + 1);
    if (!at(Tok::rparen)) {
      fail(peek(), "expected ')' to close the '(' at " + std::to_string(open.line) + ":" +
                       std::to_string(open.column) + ", or an operator ';', '|' or '#', got " + describe(peek()));
    }
    next();
    return inner;
  }
  if (!at(Tok::name)) fail(peek(), "expected a process name or '(', got " + describe(peek()));
  return process_term();
}

std::vector<std::string> Parser::name_list(const std::string& what) {
  std::vector<std::string> names;
  expect(Tok::lparen, "'(' to open the " + what);
  if (accept(Tok::rparen)) return names;
  while (true) {
    names.emplace_back(expect(Tok::name, "a port or variable name in the " + what).text);
    if (accept(Tok::rparen)) return names;
    if (!at(Tok::comma)) fail(peek(), "expected ',' or ')' in the " + what + ", got " + describe(peek()));
    next();
  }
}

void Parser::close_params() {
  if (at(Tok::greater_equal)) {
    // "Mission<x>= body": the '>' closes the parameters, the '=' stays.
    Token& token = tokens_[pos_];
    token.kind = Tok::equal;
    token.text = token.text.substr(1);
    ++token.column;
    token.first_on_line = false;
    return;
  }
  if (!at(Tok::greater)) fail(peek(), "expected ',' or '>' in the parameters, got " + describe(peek()));
  next();
}

Term Parser::process_term() {
  const Token& at_name = next();
  processes_.push_back(LocatedProcess{&at_name, std::string(at_name.text)});
  Term t = process(std::string(at_name.text));
  std::vector<const Token*> param_tokens;
  if (accept(Tok::less)) {
    if (!at(Tok::greater) && !at(Tok::greater_equal)) {
      while (true) {
        param_tokens.push_back(&peek());
        t.params.push_back(sum(1).expr);
        if (!accept(Tok::comma)) break;
      }
    }
    close_params();
  }
  if (at(Tok::lparen)) {
    t.in_ports = name_list("in ports of '" + t.name + "'");
    if (at(Tok::lparen)) t.out_ports = name_list("out ports of '" + t.name + "'");
  }
  if (accept(Tok::arrow)) t.results = name_list("results of '" + t.name + "'");
  param_tokens_ = std::move(param_tokens);
  return t;
}

// ------------------------------------------------------------ expressions

Expr Parser::expr() { return sum(0).expr; }
Expr Parser::comparison() { return comparison_node(0).expr; }

bool compare_op(Tok kind, CompareOp& op) {
  switch (kind) {
    case Tok::less: op = CompareOp::less; return true;
    case Tok::greater: op = CompareOp::greater; return true;
    case Tok::less_equal: op = CompareOp::less_equal; return true;
    case Tok::greater_equal: op = CompareOp::greater_equal; return true;
    case Tok::equal: op = CompareOp::equal; return true;
    case Tok::not_equal: op = CompareOp::not_equal; return true;
    case Tok::end:
    case Tok::name:
    case Tok::number:
    case Tok::lparen:
    case Tok::rparen:
    case Tok::comma:
    case Tok::semicolon:
    case Tok::bar:
    case Tok::hash:
    case Tok::plus:
    case Tok::minus:
    case Tok::star:
    case Tok::slash:
    case Tok::arrow: return false;
  }
  return false;
}

Parser::Node Parser::comparison_node(int nesting) {
  Node left = sum(nesting);
  CompareOp op = CompareOp::equal;
  if (!compare_op(peek().kind, op)) return left;
  const Token& at_op = next();
  Node right = sum(nesting);
  const int depth = std::max(left.depth, right.depth) + 1;
  check_depth(depth, at_op);
  return Node{compare(op, std::move(left.expr), std::move(right.expr)), depth};
}

Parser::Node Parser::sum(int nesting) {
  Node left = product(nesting);
  while (at(Tok::plus) || at(Tok::minus)) {
    const Token& at_op = next();
    Node right = product(nesting);
    const int depth = std::max(left.depth, right.depth) + 1;
    check_depth(depth, at_op);
    left = Node{binary(at_op.kind == Tok::plus ? ExprKind::add : ExprKind::subtract, std::move(left.expr),
                       std::move(right.expr)),
                depth};
  }
  return left;
}

Parser::Node Parser::product(int nesting) {
  Node left = unary(nesting);
  while (at(Tok::star) || at(Tok::slash)) {
    const Token& at_op = next();
    Node right = unary(nesting);
    const int depth = std::max(left.depth, right.depth) + 1;
    check_depth(depth, at_op);
    left = Node{binary(at_op.kind == Tok::star ? ExprKind::multiply : ExprKind::divide, std::move(left.expr),
                       std::move(right.expr)),
                depth};
  }
  return left;
}

Parser::Node Parser::unary(int nesting) {
  if (!at(Tok::minus)) return atom(nesting);
  const Token& minus = next();
  check_depth(nesting + 1, minus);
  if (at(Tok::number)) return Node{number(-next().number), 1};  // "-3" is the literal -3
  Node operand = unary(nesting + 1);
  check_depth(operand.depth + 1, minus);
  return Node{negate(std::move(operand.expr)), operand.depth + 1};
}

Parser::Node Parser::atom(int nesting) {
  const Token& first = peek();
  check_depth(nesting + 1, first);
  switch (first.kind) {
    case Tok::number: next(); return Node{number(first.number), 1};
    case Tok::name: {
      next();
      if (!at(Tok::lparen)) return Node{name(std::string(first.text)), 1};
      next();
      Expr e = call(std::string(first.text), {});
      int depth = 1;
      if (!accept(Tok::rparen)) {
        while (true) {
          Node arg = comparison_node(nesting + 1);
          depth = std::max(depth, arg.depth + 1);
          e.args.push_back(std::move(arg.expr));
          if (accept(Tok::rparen)) break;
          if (!at(Tok::comma)) {
            fail(peek(), "expected ',' or ')' in the arguments of '" + e.name + "', got " + describe(peek()));
          }
          next();
        }
      }
      check_depth(depth, first);
      return Node{std::move(e), depth};
    }
    case Tok::lparen: {
      next();
      if (accept(Tok::rparen)) return Node{tuple({}), 1};
      Node element = comparison_node(nesting + 1);
      if (accept(Tok::rparen)) return element;  // parentheses only group
      if (!at(Tok::comma)) fail(peek(), "expected ',' or ')' after " + describe(first) + ", got " + describe(peek()));
      Expr t = tuple({});
      int depth = element.depth + 1;
      t.args.push_back(std::move(element.expr));
      while (accept(Tok::comma)) {
        if (at(Tok::rparen)) break;  // a trailing comma: (a,) is a 1-tuple
        Node more = comparison_node(nesting + 1);
        depth = std::max(depth, more.depth + 1);
        t.args.push_back(std::move(more.expr));
      }
      if (!at(Tok::rparen)) fail(peek(), "expected ',' or ')' in the tuple, got " + describe(peek()));
      next();
      check_depth(depth, first);
      return Node{std::move(t), depth};
    }
    case Tok::bar: {
      next();
      Node inner = sum(nesting + 1);
      expect(Tok::bar, "'|' to close the norm |...|");
      check_depth(inner.depth + 1, first);
      return Node{norm(std::move(inner.expr)), inner.depth + 1};
    }
    case Tok::end:
    case Tok::less:
    case Tok::greater:
    case Tok::less_equal:
    case Tok::greater_equal:
    case Tok::equal:
    case Tok::not_equal:
    case Tok::rparen:
    case Tok::comma:
    case Tok::semicolon:
    case Tok::hash:
    case Tok::plus:
    case Tok::minus:
    case Tok::star:
    case Tok::slash:
    case Tok::arrow: break;
  }
  fail(first, "expected a number, a name, '(' or '|', got " + describe(first));
}

// -------------------------------------------------------------- programs

Definition Parser::definition() {
  if (!at(Tok::name)) {
    fail(peek(), "expected a definition (Name<params>(ins)(outs) = body), got " + describe(peek()));
  }
  const Token& at_name = peek();
  Term header = process_term();
  processes_.pop_back();  // a header is not a process of any term
  Definition d;
  d.name = header.name;
  for (std::size_t i = 0; i < header.params.size(); ++i) {
    if (header.params[i].kind != ExprKind::name) {
      fail(*param_tokens_[i], "the parameters of a definition must be names, got '" + to_string(header.params[i]) +
                                  "' in the definition of '" + d.name + "'");
    }
    d.params.push_back(header.params[i].name);
  }
  d.in_ports = std::move(header.in_ports);
  d.out_ports = std::move(header.out_ports);
  d.results = std::move(header.results);
  if (!at(Tok::equal)) {
    fail(peek(), "expected '=' to define '" + d.name + "', got " + describe(peek()) +
                     " (or is an operator ';', '|' or '#' missing before '" + std::string(at_name.text) + "'?)");
  }
  next();
  d.body = term();
  return d;
}

Program Parser::program() {
  Program p;
  std::vector<std::pair<int, int>> positions;
  while (!at(Tok::end)) {
    const Token& start = peek();
    Definition d = definition();
    // The comment lines directly above a definition are its comment.
    std::vector<std::string> lines;
    int expected = start.line - 1;
    for (auto it = comments_.rbegin(); it != comments_.rend(); ++it) {
      if (it->line > expected) continue;
      if (it->line < expected) break;
      lines.insert(lines.begin(), it->text);
      --expected;
    }
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (i > 0) d.comment += '\n';
      d.comment += lines[i];
    }
    for (std::size_t i = 0; i < p.definitions.size(); ++i) {
      if (p.definitions[i].name == d.name) {
        fail(start, "duplicate definition of '" + d.name + "' (first at " + std::to_string(positions[i].first) + ":" +
                        std::to_string(positions[i].second) + ")");
      }
    }
    positions.emplace_back(start.line, start.column);
    p.definitions.push_back(std::move(d));
  }
  return p;
}

void Parser::expect_end(const std::string& after) {
  if (!at(Tok::end)) fail(peek(), "unexpected " + describe(peek()) + " after " + after);
}

}  // namespace detail

Term parse_term(std::string_view text, const std::string& source_name) {
  detail::Parser parser(text, source_name);
  Term t = parser.term();
  parser.expect_end("the term (expected an operator ';', '|', '#' or the end)");
  return t;
}

Expr parse_expr(std::string_view text, const std::string& source_name) {
  detail::Parser parser(text, source_name);
  Expr e = parser.expr();
  parser.expect_end("the expression");
  return e;
}

Expr parse_condition(std::string_view text, const std::string& source_name) {
  detail::Parser parser(text, source_name);
  Expr e = parser.comparison();
  parser.expect_end("the condition");
  return e;
}

Program parse_program(std::string_view text, const std::string& source_name) {
  detail::Parser parser(text, source_name);
  return parser.program();
}

}  // namespace p3at::verifier::pars
