// What the verifier computes on PARS terms: the abort condition Ω (Def. 9),
// hiding and projection (Defs. 5 and 6) and structural equivalence (Def. 7).

#include <doctest/doctest.h>

#include <string>

#include "p3at/verifier/pars/abort_condition.hpp"
#include "p3at/verifier/pars/equivalence.hpp"
#include "p3at/verifier/pars/parser.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/pars/projection.hpp"

namespace pars = p3at::verifier::pars;

namespace {
std::string omega(const std::string& term) { return pars::to_string(pars::abort_condition(pars::parse_term(term))); }
}  // namespace

TEST_SUITE("abort condition (Def. 9)") {
  TEST_CASE("a condition process: its comparison") {
    CHECK(omega("EQ<a, b>") == "a = b");
    CHECK(omega("NEQ<a, b>") == "a != b");
    CHECK(omega("LT<x, 10>") == "x < 10");
    CHECK(omega("GT<x, 10>") == "x > 10");
    CHECK(omega("LEQ<x, 10>") == "x <= 10");
    CHECK(omega("GEQ<x + 1, y>") == "x + 1 >= y");
    // The translator's triggers.
    CHECK(omega("Is_at_goal<(13, 4), 0.3>(od_robot1)") == "|od_robot1 - (13, 4)| <= 0.3");
    CHECK(omega("Has_turned<90, 0>(od_robot1)") == "turned(od_robot1) >= 90");
    CHECK(omega("Has_turned<90, 5>(od_robot1)") == "turned(od_robot1) >= 85");
    CHECK(omega("Has_turned<a, 5>(od)") == "turned(od) >= a - 5");
    CHECK(omega("Got_message<m>(msg_m)") == "received(msg_m)");
    CHECK(omega("Message_sent<m>(ack_m)") == "acked(ack_m)");
  }
  TEST_CASE("any other process never aborts by itself") {
    CHECK(omega("Move_to<g>(od)(c)") == "never");
    CHECK(omega("Stop()(v) | Spin<40>()(v)") == "never");
    CHECK(omega("robot1.next") == "never");
    // A condition process with the wrong parameters has no condition.
    CHECK(pars::is_condition_process(pars::parse_term("EQ<a>")));
    CHECK_FALSE(pars::condition_of(pars::parse_term("EQ<a>")).has_value());
    CHECK_FALSE(pars::is_condition_process(pars::parse_term("Coop<1>")));
  }
  TEST_CASE("Ω(P | Q) = Ω(P) ∨ Ω(Q) and Ω(P # Q) = Ω(P) ∨ Ω(Q)") {
    CHECK(omega("EQ<a, b> | LT<c, d>") == "a = b or c < d");
    CHECK(omega("EQ<a, b> # LT<c, d>") == "a = b or c < d");
    CHECK(omega("Move<g>()(v) # LT<c, d> | GT<e, f>") == "c < d or e > f");
  }
  TEST_CASE("Ω(P ; Q) = Ω(P) ; Ω(Q), and X ; never = X") {
    CHECK(omega("EQ<a, b> ; GT<c, d>") == "a = b ; c > d");
    CHECK(omega("EQ<a, b> ; GT<c, d> ; LT<e, f>") == "a = b ; c > d ; e < f");
    CHECK(omega("EQ<a, b> ; Move<g>()(v)") == "a = b");
    CHECK(omega("Move<g>()(v) ; EQ<a, b>") == "never ; a = b");
    // ';' binds tighter than "or" in the printed condition.
    CHECK(omega("(EQ<a, b> | LT<c, d>) ; GT<e, f>") == "(a = b or c < d) ; e > f");
    CHECK(omega("EQ<a, b> ; GT<e, f> | LT<c, d>") == "a = b ; e > f or c < d");
  }
  TEST_CASE("a state's Ω is its triggers' conditions (calls of other states never abort)") {
    CHECK(omega("Stop()(v) # Got_message<m>(msg_m) ; robot1.next") == "received(msg_m)");
    CHECK(omega("(Coop<1>(a)(v) | Move_to<g>(od)(a)) # Is_at_goal<(1, 2), 0.5>(od) ; r.s1 # Got_message<m>(msg_m) ; r.s2") ==
          "|od - (1, 2)| <= 0.5 or received(msg_m)");
  }
  TEST_CASE("Ω of a tail-recursive definition is its body's, without the recursion") {
    const pars::Program p = pars::parse_program("P<x> = (NEQ<x, 10> | Move<x>()(v)) ; P<x + 1>\n"
                                                "Q<x> = Move<x>()(v) ; Q<x>");
    CHECK(pars::to_string(pars::abort_condition(p.definitions[0])) == "x != 10");
    CHECK(pars::abort_condition(p.definitions[1]).kind == pars::Condition::Kind::never);
    CHECK(pars::abort_condition(p.definitions[0]).parts.empty());  // one atom, not a composition
  }
}

TEST_SUITE("hiding and projection (Defs. 5 and 6)") {
  TEST_CASE("hide replaces the processes not in S by i") {
    const pars::Term t = pars::parse_term("Delay<a> ; (Delay<b> # At<r, p> # Out<c, r>) | Comm<d>(x)(y)");
    CHECK(pars::to_string(pars::hide(t, {"Delay", "At"})) == "Delay<a> ; (Delay<b> # At<r, p> # i) | i");
  }
  TEST_CASE("adjacent internal actions group: i ; i = i, i | i = i, i # i = i") {
    CHECK(pars::to_string(pars::group_internal(pars::parse_term("A ; i ; i ; B ; i"))) == "A ; i ; B ; i");
    CHECK(pars::to_string(pars::group_internal(pars::parse_term("i | i | i"))) == "i");
    CHECK(pars::to_string(pars::group_internal(pars::parse_term("(i ; i) # (i | i)"))) == "i");
    CHECK(pars::to_string(pars::group_internal(pars::parse_term("A # i # i"))) == "A # i");
  }
  TEST_CASE("projection hides, groups and removes what is hidden") {
    const pars::Term t =
        pars::parse_term("Delay<a> ; (Delay<b> # At<r, p> # Out<c, r> # In<v, u>) | Env<w>(p)(o) | Comm<d>(x)(y)");
    const auto projected = pars::project(t, {"Delay", "At"});
    REQUIRE(projected.has_value());
    CHECK(pars::to_string(*projected) == "Delay<a> ; (Delay<b> # At<r, p>)");
    // Onto At alone: the Delays go too, and single parts lose their composition.
    CHECK(pars::to_string(*pars::project(t, {"At"})) == "At<r, p>");
    CHECK_FALSE(pars::project(t, {"Sonar"}).has_value());
    // By a predicate: only robot r2's At.
    const pars::Term two = pars::parse_term("At<r1, p> | At<r2, q>");
    const auto only_r2 = pars::project(two, [](const pars::Term& p) { return p.params.at(0) == pars::name("r2"); });
    CHECK(pars::to_string(*only_r2) == "At<r2, q>");
    CHECK(pars::process_names(t) == std::set<std::string>{"At", "Comm", "Delay", "Env", "In", "Out"});
  }
}

TEST_SUITE("structural equivalence (Def. 7)") {
  TEST_CASE("the paper's example: equal structure posts the parameter constraints") {
    // (Sys')^n projected onto Q = Delay_t1 ; (Delay_t2 # At_a).
    const pars::Term system = pars::parse_term("Delay<(n - 1) * t> ; (Delay<t> # At<f(p)>)");
    const pars::Term q = pars::parse_term("Delay<t1> ; (Delay<t2> # At<a>)");
    const pars::StructuralMatch m = pars::structurally_equivalent(system, q);
    REQUIRE(m.equivalent);
    CHECK(m.mismatch.empty());
    REQUIRE(m.bindings.size() == 3);
    CHECK(m.bindings[0].process == "Delay");
    CHECK(pars::to_string(m.bindings[0].left) == "(n - 1) * t");
    CHECK(m.bindings[0].right == pars::name("t1"));
    CHECK(pars::to_string(m.bindings[1].left) == "t");
    CHECK(m.bindings[2].process == "At");
    CHECK(pars::to_string(m.bindings[2].left) == "f(p)");
    CHECK(m.bindings[2].right == pars::name("a"));
  }
  TEST_CASE("P = Q, and compositions are compared flattened (the operators are associative)") {
    CHECK(pars::structurally_equivalent(pars::parse_term("A<1>"), pars::parse_term("A<1>")).equivalent);
    CHECK(pars::structurally_equivalent(pars::parse_term("(a ; b) ; c"), pars::parse_term("a ; (b ; c)")).equivalent);
    CHECK(pars::structurally_equivalent(pars::parse_term("a | b # c"), pars::parse_term("(a | b) # c")).equivalent);
    // Ports are wiring, not structure.
    CHECK(pars::structurally_equivalent(pars::parse_term("A<x>(p)(q)"), pars::parse_term("A<y>")).equivalent);
  }
  TEST_CASE("different operators, part counts, names or arities are not equivalent, and say where") {
    const auto m1 = pars::structurally_equivalent(pars::parse_term("Delay<t> ; (Delay<w> # At<r, p>)"),
                                                  pars::parse_term("Delay<t1> ; (Delay<t2> | At<r, q>)"));
    CHECK_FALSE(m1.equivalent);
    CHECK(m1.bindings.empty());
    CHECK(m1.mismatch ==
          "'Delay<w> # At<r, p>' and 'Delay<t2> | At<r, q>' differ: a '#' composition of 2 parts vs a '|' "
          "composition of 2 parts");
    const auto m2 = pars::structurally_equivalent(pars::parse_term("a ; b ; c"), pars::parse_term("a ; b"));
    CHECK(m2.mismatch == "'a ; b ; c' and 'a ; b' differ: a ';' composition of 3 parts vs a ';' composition of 2 parts");
    const auto m3 = pars::structurally_equivalent(pars::parse_term("Delay<t> ; At<r, p>"), pars::parse_term("Delay<t> ; Put<r, p>"));
    CHECK(m3.mismatch == "'At<r, p>' and 'Put<r, p>' differ: process At vs process Put");
    const auto m4 = pars::structurally_equivalent(pars::parse_term("At<r, p>"), pars::parse_term("At<r>"));
    CHECK(m4.mismatch == "'At<r, p>' and 'At<r>' differ: At with 2 parameters vs 1 parameter");
    const auto m5 = pars::structurally_equivalent(pars::parse_term("At<r, p>"), pars::parse_term("Delay<t> ; At<r, p>"));
    CHECK(m5.mismatch == "'At<r, p>' and 'Delay<t> ; At<r, p>' differ: the process At vs a ';' composition of 2 parts");
  }
}
