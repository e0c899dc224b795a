// PARS text: the parser, the printer and their round trip (docs/pars.md,
// "Syntax"), including the seed paper's listing shapes and located errors.

#include <doctest/doctest.h>

#include <cstdint>
#include <functional>
#include <string>

#include "p3at/verifier/pars/parser.hpp"
#include "p3at/verifier/pars/printer.hpp"

namespace pars = p3at::verifier::pars;
using pars::Op;

namespace {

// The error text (source:line:column: detail) parsing `text` as a term, or "no error".
std::string term_error(const std::string& text) {
  try {
    (void)pars::parse_term(text, "t.pars");
  } catch (const pars::ParseError& e) {
    return e.what();
  }
  return "no error";
}

std::string program_error(const std::string& text) {
  try {
    (void)pars::parse_program(text, "p.pars");
  } catch (const pars::ParseError& e) {
    return e.what();
  }
  return "no error";
}

// Prints canonically: parsing it and printing again gives the same text and an equal term.
void check_canonical(const std::string& text) {
  const pars::Term t = pars::parse_term(text);
  CHECK(pars::to_string(t) == text);
  CHECK(pars::parse_term(pars::to_string(t)) == t);
}

}  // namespace

TEST_SUITE("terms") {
  TEST_CASE("a process: name, parameters, in ports, out ports, results") {
    const pars::Term t = pars::parse_term("Coop<1, 1, 1, G3A>(piM2, cV3, cC5, cC6)(vo2) -> (done)");
    REQUIRE(t.is_process());
    CHECK(t.name == "Coop");
    REQUIRE(t.params.size() == 4);
    CHECK(t.params[0] == pars::number(1));
    CHECK(t.params[3] == pars::name("G3A"));
    CHECK(t.in_ports == std::vector<std::string>{"piM2", "cV3", "cC5", "cC6"});
    CHECK(t.out_ports == std::vector<std::string>{"vo2"});
    CHECK(t.results == std::vector<std::string>{"done"});
  }

  TEST_CASE("one port list is the in ports; () () and <> are the same as none") {
    const pars::Term cond = pars::parse_term("Is_at_goal<G2B>(piM)");
    CHECK(cond.in_ports == std::vector<std::string>{"piM"});
    CHECK(cond.out_ports.empty());
    CHECK(pars::parse_term("Stop<>()()") == pars::process("Stop"));
    CHECK(pars::to_string(pars::parse_term("Stop<>()()")) == "Stop");
    CHECK(pars::to_string(pars::parse_term("Noise<q>()(c3)")) == "Noise<q>()(c3)");
  }

  TEST_CASE("precedence: ';' binds tightest, then '|', then '#'") {
    const pars::Term t = pars::parse_term("a ; b | c # d");
    REQUIRE_FALSE(t.is_process());
    CHECK(t.op == Op::disabling);
    REQUIRE(t.parts.size() == 2);
    CHECK(t.parts[0].op == Op::parallel);
    CHECK(t.parts[0].parts[0] == pars::sequence({pars::process("a"), pars::process("b")}));
    CHECK(t.parts[1] == pars::process("d"));
    // eq. (5): two sequences in parallel, no parentheses needed around them.
    const pars::Term eq5 = pars::parse_term("Delay<t1> ; (Delay<t2> # At<r1, p>) | Delay<t3> ; (Delay<t4> # At<r2, q>)");
    CHECK(eq5.op == Op::parallel);
    CHECK(eq5.parts[0].op == Op::sequence);
    CHECK(eq5.parts[0].parts[1].op == Op::disabling);
  }

  TEST_CASE("chains are n-ary; parentheses around the same operator are kept") {
    const pars::Term flat = pars::parse_term("a ; b ; c");
    CHECK(flat.parts.size() == 3);
    const pars::Term nested = pars::parse_term("(a ; b) ; c");
    REQUIRE(nested.parts.size() == 2);
    CHECK(nested.parts[0] == pars::sequence({pars::process("a"), pars::process("b")}));
    CHECK_FALSE(flat == nested);
    CHECK(pars::flatten(nested) == flat);
  }

  TEST_CASE("the printer parenthesises minimally and correctly") {
    check_canonical("a ; b ; c");
    check_canonical("(a ; b) ; c");
    check_canonical("a ; (b ; c)");
    check_canonical("a ; b | c # d");
    check_canonical("a ; (b | c) ; (d # e)");
    check_canonical("(a # b) | c");
    check_canonical("a | (b | c) | d");
    check_canonical("Delay<t1> ; (Delay<t2> # At<r1, p>) | Delay<t3> ; (Delay<t4> # At<r2, q>)");
    // Redundant parentheses go.
    CHECK(pars::to_string(pars::parse_term("((a ; b)) | (c)")) == "a ; b | c");
    // Built trees print so that they parse back equal.
    const pars::Term built = pars::parallel({pars::parallel({pars::process("a"), pars::process("b")}), pars::process("c")});
    CHECK(pars::to_string(built) == "(a | b) | c");
    CHECK(pars::parse_term(pars::to_string(built)) == built);
  }

  TEST_CASE("names may contain dots; the internal action is i") {
    const pars::Term t = pars::parse_term("robot1.bound_ow2 ; i");
    CHECK(t.parts[0].name == "robot1.bound_ow2");
    CHECK(pars::is_internal_action(t.parts[1]));
  }
}

TEST_SUITE("expressions") {
  TEST_CASE("arithmetic, calls, tuples and norms print with minimal parentheses") {
    const auto a = pars::name("a"), b = pars::name("b"), c = pars::name("c");
    CHECK(pars::to_string(pars::subtract(a, pars::subtract(b, c))) == "a - (b - c)");
    CHECK(pars::to_string(pars::subtract(pars::subtract(a, b), c)) == "a - b - c");
    CHECK(pars::to_string(pars::multiply(pars::add(a, b), c)) == "(a + b) * c");
    CHECK(pars::to_string(pars::add(a, pars::multiply(b, c))) == "a + b * c");
    CHECK(pars::to_string(pars::divide(a, pars::multiply(b, c))) == "a / (b * c)");
    CHECK(pars::to_string(pars::negate(pars::number(3))) == "-(3)");
    CHECK(pars::to_string(pars::number(-3)) == "-3");
    CHECK(pars::to_string(pars::negate(pars::add(a, b))) == "-(a + b)");
    CHECK(pars::to_string(pars::negate(pars::negate(a))) == "--a");
    CHECK(pars::to_string(pars::tuple({a})) == "(a,)");
    CHECK(pars::to_string(pars::tuple({})) == "()");
    CHECK(pars::to_string(pars::norm(pars::subtract(pars::name("p"), pars::point(19.75, 18)))) == "|p - (19.75, 18)|");
    CHECK(pars::to_string(pars::call("z", {pars::name("u"), pars::name("t")})) == "z(u, t)");
    CHECK(pars::to_string(pars::compare(pars::CompareOp::less_equal, a, pars::number(0.3))) == "a <= 0.3");
  }

  TEST_CASE("each prints back to an equal expression") {
    const auto a = pars::name("a"), b = pars::name("b");
    const pars::Expr cases[] = {
        pars::subtract(a, pars::subtract(b, pars::number(-1))),
        pars::negate(pars::number(3)),
        pars::number(-3),
        pars::negate(pars::number(-3)),
        pars::subtract(a, pars::number(-2)),
        pars::multiply(pars::number(-2), a),
        pars::negate(pars::negate(a)),
        pars::tuple({a}),
        pars::tuple({}),
        pars::tuple({pars::point(0, 2.5), pars::point(24, 2.5)}),
        pars::number(1e21),
        pars::number(1.5e-7),
        pars::number(0.1),
        pars::call("MoG", {pars::tuple({pars::number(1), pars::number(0.35), pars::number(0.01)})}),
        pars::norm(pars::norm(pars::subtract(a, b))),
        pars::add(pars::name("r"), pars::multiply(pars::multiply(pars::name("u"), pars::call("z", {a, b})), pars::name("t"))),
    };
    for (const pars::Expr& e : cases) {
      CAPTURE(pars::to_string(e));
      CHECK(pars::parse_expr(pars::to_string(e)) == e);
    }
    const pars::Expr cmp = pars::compare(pars::CompareOp::greater, pars::norm(pars::subtract(a, b)), pars::number(1));
    CHECK(pars::parse_condition(pars::to_string(cmp)) == cmp);
  }

  TEST_CASE("a comparison in a parameter is parenthesised (a bare '>' would close the list)") {
    const pars::Term t = pars::process("Guard", {pars::compare(pars::CompareOp::greater, pars::name("x"), pars::number(2))});
    CHECK(pars::to_string(t) == "Guard<(x > 2)>");
    CHECK(pars::parse_term(pars::to_string(t)) == t);
  }

  TEST_CASE("constant values and points") {
    CHECK(pars::constant_value(pars::parse_expr("3 * 60 - -5")) == doctest::Approx(185));
    CHECK_FALSE(pars::constant_value(pars::parse_expr("3 * t")).has_value());
    CHECK_FALSE(pars::constant_value(pars::parse_expr("1 / 0")).has_value());
    const auto p = pars::constant_point(pars::parse_expr("(19.75, 18 - 0.5)"));
    REQUIRE(p.has_value());
    CHECK(p->second == doctest::Approx(17.5));
  }
}

TEST_SUITE("programs") {
  // The seed paper's listing in VI.A, in our syntax (its lines 1-17 with the
  // operators that the typesetting lost), and its system process.
  constexpr const char* kPaperListing = R"(# A small portion of the paper's Mission process.
Mission(piM, piM2, obM, obM2, hM, hM2, odM, odM2)(vo, vo2) =
    (Is_at_goal<G2B>(piM) ; Put_message<S1>()(cG2)) |
    (Got_message<S1>(cG2) ;
     ((Coop<1, 1, 1, G3A>(piM2, cV3, cC5, cC6)(vo2) |
       Move_to<G3A, drop2500>(piM2)(cV3) |
       Noise<Z0, G3A>(piM2)(cC5) |
       Avoid_Obstacles<Z0, G3A>(piM2, obM2)(cC6)) #
      (Is_at_goal<G3A>(piM2) ; Spin<G90>(hM2)(vo2)) #
      (Is_at_head<G90>(hM2) ;
       (Coop<1, 1, 1, G3B>(piM2, cV4, cC7, cC8)(vo2) |
        Move_to<G3B, drop2500>(piM2)(cV4) |
        Noise<Z0, G3B>(piM2)(cC7) |
        Avoid_Obstacles<Z0, G3B>(piM2, obM2)(cC8)))))

# The robot template: odometry q and true position r, both random.
Robot<r, q>(v)(p, d) = (At<r> # Delay<t> # Out<p, r> # Out<d, q> # In<v, u>) ; Robot<r + u * z(u, t) * t, q + u * t>(v)(p, d)

Sys = Mission(c1, c2, c3, c4, c5, c6, c7, c8)(c9, c10) |
      Robot1<P01, Z0, H0>(c9)(c7, c3, c5, c1) |
      Robot2<P02, Z0, H0>(c10)(c8, c4, c6, c2)
)";

  TEST_CASE("the paper's listing parses into definitions with comments") {
    const pars::Program p = pars::parse_program(kPaperListing, "listing.pars");
    REQUIRE(p.definitions.size() == 3);
    const pars::Definition& mission = p.definitions[0];
    CHECK(mission.name == "Mission");
    CHECK(mission.comment == "A small portion of the paper's Mission process.");
    CHECK(mission.in_ports.size() == 8);
    CHECK(mission.out_ports == std::vector<std::string>{"vo", "vo2"});
    // Two threads in parallel: robot 1 reaching G2B, robot 2's chain of states.
    REQUIRE(mission.body.op == Op::parallel);
    const pars::Term& chain = mission.body.parts[1];
    REQUIRE(chain.op == Op::sequence);
    CHECK(chain.parts[0].name == "Got_message");
    const pars::Term& state = chain.parts[1];
    REQUIRE(state.op == Op::disabling);
    REQUIRE(state.parts.size() == 3);
    CHECK(state.parts[0].op == Op::parallel);  // GoToGuarded: Coop | Move_to | Noise | Avoid_Obstacles
    CHECK(state.parts[0].parts.size() == 4);
    CHECK(state.parts[1] == pars::parse_term("Is_at_goal<G3A>(piM2) ; Spin<G90>(hM2)(vo2)"));
    // The next state's network is in sequence after its trigger, as one part.
    REQUIRE(state.parts[2].op == Op::sequence);
    CHECK(state.parts[2].parts[1].op == Op::parallel);
    CHECK(state.parts[2].parts[1].parts[0].name == "Coop");
    const pars::Definition& robot = p.definitions[1];
    CHECK(robot.params == std::vector<std::string>{"r", "q"});
    CHECK(pars::is_tail_recursive(robot));
    CHECK(pars::to_string(pars::tail_call(robot)->params[0]) == "r + u * z(u, t) * t");
    CHECK_FALSE(pars::is_tail_recursive(mission));
    CHECK(p.definitions[2].body.parts.size() == 3);
  }

  TEST_CASE("a program prints back to an equal program, comments included") {
    const pars::Program p = pars::parse_program(kPaperListing);
    const std::string printed = pars::to_string(p);
    CHECK(pars::parse_program(printed) == p);
    CHECK(pars::to_string(pars::parse_program(printed)) == printed);
    // Long bodies are broken with the operator ending each line, never starting one.
    CHECK(printed.find("\n    (Is_at_goal<G2B>(piM) ; Put_message<S1>()(cG2)) |\n") != std::string::npos);
    CHECK(printed.find("\n#") == printed.find("\n# The robot template"));
  }

  TEST_CASE("a '#' first on a line is a comment; elsewhere it is the operator") {
    const pars::Program p = pars::parse_program("# one\n#\n#  indented\nA = B # C\n\n# two\nD = E\n# dangling\n");
    REQUIRE(p.definitions.size() == 2);
    CHECK(p.definitions[0].comment == "one\n\n indented");
    CHECK(p.definitions[0].body == pars::disabling({pars::process("B"), pars::process("C")}));
    CHECK(p.definitions[1].comment == "two");
    // The pitfall the printer avoids: a line that starts with '#' is not an operator.
    CHECK(pars::parse_term("B\n  # C") == pars::process("B"));
  }

  TEST_CASE("definition headers: parameters, ports, results; '>=' splits after parameters") {
    const pars::Program p = pars::parse_program("P<x, y>(a)(b) -> (v) = Q<x + 1>(a)(b)\nR<x>= S");
    CHECK(p.definitions[0].params == std::vector<std::string>{"x", "y"});
    CHECK(p.definitions[0].results == std::vector<std::string>{"v"});
    CHECK(pars::header_string(p.definitions[0]) == "P<x, y>(a)(b) -> (v)");
    CHECK(p.definitions[1].params == std::vector<std::string>{"x"});
    CHECK(p.find("R") == &p.definitions[1]);
    CHECK(p.find("T") == nullptr);
  }
}

TEST_SUITE("errors name line:column and what was expected") {
  TEST_CASE("terms") {
    CHECK(term_error("a ; ; b") == "t.pars:1:5: expected a process name or '(', got ';'");
    CHECK(term_error("") == "t.pars:1:1: expected a process name or '(', got the end of the input");
    CHECK(term_error("(a ; b") ==
          "t.pars:1:7: expected ')' to close the '(' at 1:1, or an operator ';', '|' or '#', got the end of the input");
    CHECK(term_error("a b") == "t.pars:1:3: unexpected 'b' after the term (expected an operator ';', '|', '#' or the end)");
    CHECK(term_error("A<1, 2") == "t.pars:1:7: expected ',' or '>' in the parameters, got the end of the input");
    CHECK(term_error("A(x y)") == "t.pars:1:5: expected ',' or ')' in the in ports of 'A', got 'y'");
    CHECK(term_error("A()(1)") == "t.pars:1:5: expected a port or variable name in the out ports of 'A', got '1'");
    CHECK(term_error("A -> v") == "t.pars:1:6: expected '(' to open the results of 'A', got 'v'");
    CHECK(term_error("A<(1, 2 x)>") == "t.pars:1:9: expected ',' or ')' in the tuple, got 'x'");
    // Inside parentheses a comparison is allowed, so '>' there does not close the list.
    CHECK(term_error("A<(1, 2>") == "t.pars:1:9: expected a number, a name, '(' or '|', got the end of the input");
    CHECK(term_error("A<|x>") == "t.pars:1:5: expected '|' to close the norm |...|, got '>'");
    CHECK(term_error("A<f(1 2)>") == "t.pars:1:7: expected ',' or ')' in the arguments of 'f', got '2'");
    CHECK(term_error("A<>") == "no error");
    CHECK(term_error("A<*>") == "t.pars:1:3: expected a number, a name, '(' or '|', got '*'");
  }
  TEST_CASE("positions count lines and columns from 1") {
    CHECK(term_error("a ;\n  b |\n    )") == "t.pars:3:5: expected a process name or '(', got ')'");
    CHECK(term_error("# comment\n\ta ; ;") == "t.pars:2:6: expected a process name or '(', got ';'");
  }
  TEST_CASE("characters and numbers") {
    CHECK(term_error("a @ b") == "t.pars:1:3: unexpected character '@'");
    CHECK(term_error("a \xC3\xA9") == "t.pars:1:3: unexpected character '\\xC3'");
    CHECK(term_error("A<x ! y>") == "t.pars:1:5: unexpected character '!' (did you mean '!='?)");
    CHECK(term_error("A<1.>") == "t.pars:1:5: expected a digit after the decimal point");
    CHECK(term_error("A<1e999>") == "t.pars:1:3: number out of range: 1e999");
  }
  TEST_CASE("hostile nesting stops at a limit instead of exhausting the stack") {
    const std::string deep = std::string(300, '(') + "a" + std::string(300, ')');
    CHECK(term_error(deep) == "t.pars:1:201: nested too deeply (more than 200 levels)");
    std::string sum = "A<";
    for (int i = 0; i < 300; ++i) sum += "1 + ";
    sum += "1>";
    CHECK(term_error(sum).find("nested too deeply (more than 200 levels)") != std::string::npos);
    CHECK(term_error("A<" + std::string(300, '-') + "x>").find("nested too deeply") != std::string::npos);
    std::string fine = "A<";
    for (int i = 0; i < 150; ++i) fine += "1 + ";
    CHECK(term_error(fine + "1>") == "no error");
  }
  TEST_CASE("programs") {
    CHECK(program_error("A = B C ; D") ==
          "p.pars:1:9: expected '=' to define 'C', got ';' (or is an operator ';', '|' or '#' missing before 'C'?)");
    CHECK(program_error("A = B\nA = C") == "p.pars:2:1: duplicate definition of 'A' (first at 1:1)");
    CHECK(program_error("A<x, 1 + y> = B") ==
          "p.pars:1:6: the parameters of a definition must be names, got '1 + y' in the definition of 'A'");
    CHECK(program_error("= B") == "p.pars:1:1: expected a definition (Name<params>(ins)(outs) = body), got '='");
    CHECK(program_error("A =") == "p.pars:1:4: expected a process name or '(', got the end of the input");
    CHECK(program_error("") == "no error");
  }
}

// Random terms (a fixed-seed generator, so the test is the same every run)
// print and parse back equal: the printer never drops a needed parenthesis.
TEST_CASE("random terms and expressions round-trip") {
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  const auto next = [&state](std::uint64_t n) -> std::size_t {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (state >> 33) % n;
  };
  const double numbers[] = {0, 1, -1, 0.5, -2.25, 1e-7, 3e21, 19.75, -0.0};
  std::function<pars::Expr(int)> expr = [&](int depth) -> pars::Expr {
    const std::size_t k = depth > 3 ? next(2) : next(10);
    switch (k) {
      case 0: return pars::number(numbers[next(9)]);
      case 1: return pars::name(next(2) ? "x" : "robot1.y");
      case 2: return pars::negate(expr(depth + 1));
      case 3: return pars::tuple({expr(depth + 1), expr(depth + 1)});
      case 4: return pars::call("f", {expr(depth + 1)});
      case 5: return pars::norm(expr(depth + 1));
      case 6: return pars::add(expr(depth + 1), expr(depth + 1));
      case 7: return pars::subtract(expr(depth + 1), expr(depth + 1));
      case 8: return pars::multiply(expr(depth + 1), expr(depth + 1));
      default: return pars::divide(expr(depth + 1), expr(depth + 1));
    }
  };
  std::function<pars::Term(int)> term = [&](int depth) -> pars::Term {
    if (depth > 3 || next(3) == 0) {
      pars::Term p = pars::process(next(2) ? "A" : "B.c");
      for (std::size_t i = next(3); i > 0; --i) p.params.push_back(expr(0));
      if (next(2)) p.in_ports = {"i1"};
      if (next(3) == 0) p.out_ports = {"o1", "o2"};
      if (next(4) == 0) p.results = {"v"};
      return p;
    }
    std::vector<pars::Term> parts;
    for (std::size_t i = 2 + next(2); i > 0; --i) parts.push_back(term(depth + 1));
    return pars::compose(static_cast<Op>(next(3)), std::move(parts));
  };
  for (int i = 0; i < 500; ++i) {
    const pars::Term t = term(0);
    CAPTURE(pars::to_string(t));
    CHECK(pars::parse_term(pars::to_string(t)) == t);
    CHECK(pars::parse_term(pars::to_pretty_string(t, 4, 40)) == t);
  }
}

TEST_CASE("a comment's trailing carriage returns are all dropped, so it prints and reads back the same") {
  // Found by fuzz_pars_parser (a long run): "x\r\r" kept "x\r", printed as "# x\r", read back "x".
  const p3at::verifier::pars::Program p =
      p3at::verifier::pars::parse_program("# note\r\r\nA = stop\n", "crlf.pars");
  REQUIRE(p.definitions.size() == 1);
  CHECK(p.definitions[0].comment == "note");
  CHECK(p3at::verifier::pars::parse_program(p3at::verifier::pars::to_string(p), "printed.pars") == p);
}
