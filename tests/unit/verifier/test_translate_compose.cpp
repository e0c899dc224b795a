// System composition on small hand-checked systems: port matching (who feeds
// whom, O(np·nio)), the errors that explain a mismatch, and the flow function
// f(u) of the paper's two-robot example, eq. (2).

#include <doctest/doctest.h>

#include <string>

#include "p3at/verifier/pars/parser.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "p3at/verifier/translate.hpp"

namespace pars = p3at::verifier::pars;
using p3at::verifier::compose_system;

namespace {

// Eq. (2) with definitions: each program steers toward its goal g at gain k
// from the position it reads; each robot moves by the velocity it reads.
constexpr const char* kTwoRobots = R"(
PR1<r>(c)(v) = (In<c, x> # Out<v, k * (r - x)>) ; PR1<r>(c)(v)
PR2<r>(c)(v) = (In<c, x> # Out<v, k * (r - x)>) ; PR2<r>(c)(v)
Robot1<q>(v)(c) = (Out<c, q> # In<v, u> # Delay<t>) ; Robot1<q + u * t>(v)(c)
Robot2<q>(v)(c) = (Out<c, q> # In<v, u> # Delay<t>) ; Robot2<q + u * t>(v)(c)
Sys<r, p, q, s> = PR1<r>(cp1)(cv1) | PR2<p>(cp2)(cv2) | Robot1<q>(cv1)(cp1) | Robot2<s>(cv2)(cp2)
)";

std::string compose_error(const std::string& program, const std::string& system = "Sys") {
  const auto r = compose_system(pars::parse_program(program), system);
  return r.ok() ? "no error" : r.error().message;
}

}  // namespace

TEST_CASE("eq. (2): the connection graph") {
  const auto sys = compose_system(pars::parse_program(kTwoRobots));
  REQUIRE(sys.ok());
  CHECK(sys->system == "Sys");
  CHECK(sys->parameters == std::vector<std::string>{"r", "p", "q", "s"});
  REQUIRE(sys->components.size() == 4);
  CHECK(sys->components[2].label == "Robot1");
  for (const auto& c : sys->components) CHECK(c.tail_recursive);
  // Each reads one port, from its partner.
  REQUIRE(sys->connections.size() == 4);
  CHECK(sys->connections[0] == p3at::verifier::PortConnection{"cp1", 2, 0});
  CHECK(sys->connections[1] == p3at::verifier::PortConnection{"cp2", 3, 1});
  CHECK(sys->connections[2] == p3at::verifier::PortConnection{"cv1", 0, 2});
  CHECK(sys->connections[3] == p3at::verifier::PortConnection{"cv2", 1, 3});
  CHECK(sys->feeders(0) == std::vector<std::size_t>{2});
  CHECK(sys->feeders(3) == std::vector<std::size_t>{1});
}

TEST_CASE("eq. (2): the flow function follows the connections") {
  const auto sys = compose_system(pars::parse_program(kTwoRobots));
  REQUIRE(sys.ok());
  REQUIRE(sys->flow.size() == 4);
  // Robot1's q: it reads u from cv1, which PR1 writes from what it read on cp1,
  // which Robot1 itself wrote: f(q) = q + k * (r - q) * t.
  const auto* q1 = sys->find_flow("Robot1", "q");
  REQUIRE(q1 != nullptr);
  CHECK(q1->initial == pars::name("q"));
  CHECK(pars::to_string(q1->update) == "q + k * (r - q) * t");
  CHECK(q1->ports == std::vector<std::string>{"cv1", "cp1"});
  // Robot2 was initialised with s and is steered by PR2's p.
  const auto* q2 = sys->find_flow("Robot2", "q");
  REQUIRE(q2 != nullptr);
  CHECK(q2->initial == pars::name("s"));
  CHECK(pars::to_string(q2->update) == "s + k * (p - s) * t");
  // The programs keep their goals.
  CHECK(pars::to_string(sys->find_flow("PR1", "r")->update) == "r");
  CHECK(sys->find_flow("PR1", "r")->ports.empty());
  CHECK(sys->find_flow("PR1", "x") == nullptr);
  const std::string text = p3at::verifier::to_string(*sys);
  CHECK(text.find("Robot1.q <- q + k * (r - q) * t   (via cv1, cp1)") != std::string::npos);
  CHECK(text.find("  Robot1 (tail-recursive)\n    <- cv1 from PR1\n") != std::string::npos);
}

TEST_CASE("a writer that is not tail-recursive gives its port's value by name") {
  const char* program = R"(
Ctrl(c)(v) = Steer(c)(v)
Robot<q>(v)(c) = (Out<c, q> # In<v, u>) ; Robot<q + u>(v)(c)
Sys<q0> = Ctrl(pos)(vel) | Robot<q0>(vel)(pos)
)";
  const auto sys = compose_system(pars::parse_program(program));
  REQUIRE(sys.ok());
  CHECK_FALSE(sys->components[0].tail_recursive);
  CHECK(sys->components[0].defined);
  CHECK(pars::to_string(sys->find_flow("Robot", "q")->update) == "q0 + vel");
}

TEST_CASE("a cycle of same-period reads stops at the port that closes it") {
  const char* program = R"(
A<a>(x)(y) = (In<x, m> # Out<y, m + 1>) ; A<m>(x)(y)
B<b>(y)(x) = (In<y, n> # Out<x, n * 2>) ; B<n>(y)(x)
Sys = A<0>(px)(py) | B<1>(py)(px)
)";
  const auto sys = compose_system(pars::parse_program(program));
  REQUIRE(sys.ok());
  // A's m comes from px, which B writes as n * 2 with n from py, which A writes
  // as m + 1 with m from px again: the cycle closes at px.
  CHECK(pars::to_string(sys->find_flow("A", "a")->update) == "(px + 1) * 2");
  CHECK(sys->find_flow("A", "a")->ports == std::vector<std::string>{"px", "py"});
  CHECK(pars::to_string(sys->find_flow("B", "b")->update) == "py * 2 + 1");
}

TEST_CASE("basic components and repeated names are labelled") {
  const auto sys = compose_system(pars::parse_program("Sys = Sensor<s1>()(a) | Sensor<s2>()(b) | Use(a, b)"));
  REQUIRE(sys.ok());
  CHECK(sys->components[0].label == "Sensor<s1>");
  CHECK(sys->components[1].label == "Sensor<s2>");
  CHECK_FALSE(sys->components[2].defined);
  CHECK(sys->feeders(2) == std::vector<std::size_t>{0, 1});
  const auto single = compose_system(pars::parse_program("Sys = Alone<1>()(x)"));
  REQUIRE(single.ok());
  CHECK(single->components.size() == 1);
  CHECK(single->connections.empty());
}

TEST_CASE("mismatches are errors that name the port and the components") {
  CHECK(compose_error("Sys = A(x)(y) | B(y)(z)") ==
        "port 'x' read by A (A(x)(y)) is written by no component of Sys (out ports: y, z)");
  CHECK(compose_error("Sys = A()(y) | B()(y) | C(y)") ==
        "port 'y' is written by both A and B (each port needs exactly one writer)");
  CHECK(compose_error("Sys = A(y)(y)") == "A reads its own out port 'y' (an in port must be written by another component)");
  CHECK(compose_error("Sys = A()(y, y)") == "A lists out port 'y' twice");
  CHECK(compose_error("Sys = A ; B") == "the body of Sys must be a parallel composition of components, not a ';' composition: A ; B");
  CHECK(compose_error("Sys = A | (B ; C)") ==
        "component 2 of Sys is a ';' composition (B ; C); each component must be one process call");
  CHECK(compose_error("A = B", "Sys") == "no definition of 'Sys' in the program (it defines A)");
  // Flow-function problems in a TR component.
  CHECK(compose_error("R<q>(v)(c) = (Out<c, q> # In<v, u>) ; R<q + u>(v)(c)\nSys = R<1, 2>(a)(b) | S()(a)") ==
        "R passes 2 parameters to R, which takes 1 (q)");
  CHECK(compose_error("R<q>(v)(c) = (Out<c, q> # In<v, u>) ; R<q + u>(v)(c)\nSys = R<1>(a)(b, d) | S()(a)") ==
        "R connects 1 in and 2 out ports to R<q>(v)(c), which has 1 and 1");
  CHECK(compose_error("R<q>(v)(c) = (Out<w, q> # In<v, u>) ; R<q + u>(v)(c)\nSys = R<1>(a)(b) | S()(a)") ==
        "in R, Out<w, q> uses 'w', which is not one of its ports");
  CHECK(compose_error("R<q>(v)(c) = (Out<c> # In<v, u>) ; R<q + u>(v)(c)\nSys = R<1>(a)(b) | S()(a)") ==
        "in R, Out<c> is not a port operation (expected Out<port, expression>)");
  CHECK(compose_error("R<q>(v)(c) = In<v, 1 + u> ; R<q>(v)(c)\nSys = R<1>(a)(b) | S()(a)") ==
        "in R, In<v, 1 + u> is not a port operation (expected In<port, variable>)");
  CHECK(compose_error("R<q>(v)(c) = In<v, u> ; R<q, u>(v)(c)\nSys = R<1>(a)(b) | S()(a)") ==
        "R recurses with 2 parameters but takes 1");
}
