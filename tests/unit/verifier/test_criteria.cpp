// Performance criteria (docs/pars.md, "Criterion files"): the seed paper's
// eqs. (4), (5), (6) and (7) evaluated on hand-built final distributions whose
// probabilities have closed forms, and every error a criterion can give.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "p3at/mission/loader.hpp"
#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/separation.hpp"
#include "p3at/verifier/pars/printer.hpp"
#include "scratch.hpp"

namespace v = p3at::verifier;
namespace mission = p3at::mission;

namespace {

double phi(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
// P(|X - mean| < r) for an isotropic 2-D Gaussian with variance var per axis (Rayleigh).
double within_centred(double r, double var) { return 1.0 - std::exp(-r * r / (2.0 * var)); }

const mission::Mission& two_robots() {
  static const mission::Mission m =
      mission::load_mission_file(std::string(P3AT_SOURCE_DIR) + "/examples/bounding_overwatch/mission.yaml");
  return m;
}

v::RobotOutcome robot(double t_mean, double t_var, double x, double y, double pos_var) {
  v::RobotOutcome r;
  r.finish_time_s = v::Mixture1::gaussian(t_mean, t_var);
  r.final_position.mean = Eigen::Vector2d(x, y);
  r.final_position.cov = pos_var * Eigen::Matrix2d::Identity();
  return r;
}

v::Branch branch(double weight, v::RobotOutcome r1, v::RobotOutcome r2) {
  v::Branch b;
  b.weight = weight;
  b.robots = {std::move(r1), std::move(r2)};
  return b;
}

// A separation sample of the pair (0, 1): their difference at time t, with an
// isotropic error of variance var, joined to the sample before it or not.
v::SeparationSample separation_sample(double t, double x, double y, double var, bool joined) {
  v::SeparationSample s;
  s.robot_i = 0;
  s.robot_j = 1;
  s.time_s = t;
  s.difference.mean = Eigen::Vector2d(x, y);
  s.difference.cov = var * Eigen::Matrix2d::Identity();
  s.joined = joined;
  s.rigid_s = 20.0;
  return s;
}

v::SystemOutcome one_branch(v::RobotOutcome r1, v::RobotOutcome r2) {
  v::SystemOutcome o;
  o.branches.push_back(branch(1.0, std::move(r1), std::move(r2)));
  return o;
}

std::string criterion_error(const std::string& text) {
  try {
    (void)v::parse_criterion(text, "c.crit");
  } catch (const v::CriterionError& e) {
    return e.what();
  }
  return "no error";
}

std::string evaluation_error(const std::string& text, const v::SystemOutcome& outcome) {
  const auto r = v::evaluate_criterion(v::parse_criterion(text, "c.crit"), two_robots(), outcome, 0.8);
  return r.ok() ? "no error" : r.error().message;
}

constexpr const char* kEq4 = R"(# eq. (4): robot1 reaches its goal by 200 s, within 2 m
criterion reach
network Delay<t1> ; (Delay<t2> # At<robot1, p>)
constraints
  t1 <= 200
  |p - (19.75, 18)| < 2
)";

constexpr const char* kEq5 = R"(# eq. (5): robot1 arrives before robot2, each within R of its location with P > 0.8
criterion ordered_arrival
network  Delay<t1> ; (Delay<t2> # At<robot1,p>) | Delay<t3> ; (Delay<t4> # At<robot2,q>)
constraints
  t1 <= 200
  t3 <= 200
  t1 < t3
  P(|p - (19.75, 18.0)| < 2.0) > 0.8
  P(|q - (20.0, 17.5)| < 2.0) > 0.8
)";

constexpr const char* kEq6 = R"(criterion apart
network Delay<t1> ; (Delay<t2> # At<robot1, p>) |
        Delay<t3> ; (Delay<t4> # At<robot2, q>)
constraints
  t1, t3 > 0
  P(|p - q| > 1.0) > 0.8
)";

}  // namespace

TEST_SUITE("criterion files") {
  TEST_CASE("eq. (5) parses: name, network, constraints with their lines") {
    const v::Criterion c = v::parse_criterion(kEq5, "eq5.crit");
    CHECK(c.name == "ordered_arrival");
    CHECK(c.source == "eq5.crit");
    CHECK(v::pars::to_string(c.network) ==
          "Delay<t1> ; (Delay<t2> # At<robot1, p>) | Delay<t3> ; (Delay<t4> # At<robot2, q>)");
    REQUIRE(c.constraints.size() == 5);
    CHECK_FALSE(c.constraints[0].probabilistic);
    CHECK(c.constraints[0].line == 5);
    CHECK(c.constraints[0].column == 3);
    CHECK(v::to_string(c.constraints[2]) == "t1 < t3");
    CHECK(c.constraints[3].probabilistic);
    CHECK(c.constraints[3].bound == doctest::Approx(0.8));
    CHECK(c.constraints[3].bound_op == v::pars::CompareOp::greater);
    CHECK(v::to_string(c.constraints[3]) == "P(|p - (19.75, 18)| < 2) > 0.8");
  }

  TEST_CASE("to_string writes a file that reads back equal") {
    for (const char* text : {kEq4, kEq5, kEq6}) {
      const v::Criterion c = v::parse_criterion(text, "c.crit");
      CHECK(v::parse_criterion(v::to_string(c), "again.crit") == c);
    }
    CHECK(v::to_string(v::parse_criterion(kEq4, "c.crit")) ==
          "criterion reach\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>)\nconstraints\n  t1 <= 200\n"
          "  |p - (19.75, 18)| < 2\n");
    const v::Criterion several = v::parse_criterion(
        "criterion s\nnetwork At<robot1, p>\nconstraints\n  P(|p - (1, 2)| < 3 and |p - (0, 0)| > 1) >= 0.5\n", "s");
    CHECK(v::to_string(several.constraints[0]) == "P(|p - (1, 2)| < 3 and |p - (0, 0)| > 1) >= 0.5");
    CHECK(v::parse_criterion(v::to_string(several), "s") == several);
  }

  TEST_CASE("no constraints is allowed; comments anywhere on their own lines") {
    const v::Criterion c =
        v::parse_criterion("# head\ncriterion bare\n# between\nnetwork At<robot1, p>\n# tail\n", "c.crit");
    CHECK(c.constraints.empty());
    CHECK(c.network == v::pars::process("At", {v::pars::name("robot1"), v::pars::name("p")}));
  }

  TEST_CASE("load_criterion_file reads a file and names unreadable ones") {
    const std::string path = p3at::test::scratch_path("eq4.crit");
    {
      std::ofstream out(path);
      out << kEq4;
    }
    CHECK(v::load_criterion_file(path).name == "reach");
    std::remove(path.c_str());
    try {
      (void)v::load_criterion_file(path);
      FAIL("no error");
    } catch (const v::CriterionError& e) {
      CHECK(std::string(e.what()) == path + ": cannot open criterion file: No such file or directory");
      CHECK(e.line() == 0);
    }
    CHECK_THROWS_WITH_AS((void)v::load_criterion_file("/tmp"), "/tmp: cannot open criterion file: it is a directory",
                         v::CriterionError);
  }
}

TEST_SUITE("criterion errors name line:column") {
  TEST_CASE("the header and the network") {
    CHECK(criterion_error("network At<robot1, p>") ==
          "c.crit:1:1: expected 'criterion NAME' to begin the criterion, got 'network'");
    CHECK(criterion_error("criterion\nnetwork At<robot1, p>") ==
          "c.crit:2:1: expected the criterion's name after 'criterion', got 'network'");
    CHECK(criterion_error("criterion x\nconstraints\n  t < 1") ==
          "c.crit:2:1: expected 'network' and the criterion's process network on a new line, got 'constraints'");
    CHECK(criterion_error("criterion x network At<robot1, p>") ==
          "c.crit:1:13: expected 'network' and the criterion's process network on a new line, got 'network'");
    CHECK(criterion_error("criterion x\nnetwork At<robot1, p> extra") ==
          "c.crit:2:23: unexpected 'extra' after the network (expected an operator ';', '|' or '#', or "
          "'constraints' on a new line)");
    CHECK(criterion_error("criterion x\nnetwork Delay<t> ;") ==
          "c.crit:2:19: expected a process name or '(', got the end of the input");
  }
  TEST_CASE("the network's processes and variables") {
    CHECK(criterion_error("criterion x\nnetwork Delay<t> ; Foo<y>") ==
          "c.crit:2:20: unknown process 'Foo' in a criterion network (expected Delay<time variable> or "
          "At<robot, position variable>)");
    CHECK(criterion_error("criterion x\nnetwork Delay<t1, t2>") ==
          "c.crit:2:9: Delay takes one time variable, Delay<t>, got 'Delay<t1, t2>'");
    CHECK(criterion_error("criterion x\nnetwork Delay<200>") ==
          "c.crit:2:9: Delay takes one time variable, Delay<t>, got 'Delay<200>'");
    CHECK(criterion_error("criterion x\nnetwork At<robot1>") ==
          "c.crit:2:9: At takes a robot and a position variable, At<robot, p>, got 'At<robot1>'");
    CHECK(criterion_error("criterion x\nnetwork Delay<t>(c)") ==
          "c.crit:2:9: a criterion's processes have no ports or results, got 'Delay<t>(c)'");
    CHECK(criterion_error("criterion x\nnetwork Delay<t> ;\n  (Delay<t> # At<robot1, p>)") ==
          "c.crit:3:4: variable 't' appears twice in the network (first at 2:9)");
    CHECK(criterion_error("criterion x\nnetwork Delay<P>") ==
          "c.crit:2:9: 'P' is reserved (P(...) and 'and' in constraints); rename the variable");
    CHECK(criterion_error("criterion x\nnetwork At<robot1, robot1>") ==
          "c.crit:2:9: 'robot1' names both a robot and a variable");
  }
  TEST_CASE("constraints") {
    const std::string head = "criterion x\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>) | Delay<t3> ; At<robot2, q>\n"
                             "constraints\n";
    CHECK(criterion_error(head + "  t9 < 1") ==
          "c.crit:4:3: unknown variable 't9' (not a parameter of the network's Delay or At processes)");
    CHECK(criterion_error(head + "  t1 = 5") ==
          "c.crit:4:3: compare with <, <=, > or >= (for continuous variables, '=' has probability 0)");
    CHECK(criterion_error(head + "  |t1 - (1, 2)| < 2") == "c.crit:4:3: 't1' is a time, not a position (At's second parameter)");
    CHECK(criterion_error(head + "  p <= 5") ==
          "c.crit:4:3: 'p' is a position: constrain its distance, as in |p - (x, y)| < r");
    CHECK(criterion_error(head + "  2 * t1 < 5") ==
          "c.crit:4:3: expected a time comparison (t <= 200, t1 + 5 < t3) or a distance (|p - (x, y)| < r, "
          "|p - q| > d), got '2 * t1'");
    CHECK(criterion_error(head + "  t1 < t1") == "c.crit:4:3: 't1' is compared with itself");
    CHECK(criterion_error(head + "  5 < 6") == "c.crit:4:3: the comparison involves no variable");
    CHECK(criterion_error(head + "  |p - q| > -1") ==
          "c.crit:4:3: a distance is never negative: compare it with a length >= 0, got -1");
    CHECK(criterion_error(head + "  |p - p| > 1") == "c.crit:4:3: |p - p| is always 0");
    CHECK(criterion_error(head + "  |p - (1, 2)| < t1") == "c.crit:4:3: compare a distance with a constant, got 't1'");
    CHECK(criterion_error(head + "  t1, |p - (1, 2)| < 1") ==
          "c.crit:4:3: a list before a comparison must be variables only, got '|p - (1, 2)|'");
    CHECK(criterion_error(head + "  P(t1 < 5) < 0.5") ==
          "c.crit:4:13: a probability constraint is a lower bound, P(...) > x or P(...) >= x (for an upper bound, "
          "negate the event inside P)");
    CHECK(criterion_error(head + "  P(t1 < 5) > 1.5") == "c.crit:4:15: expected a probability between 0 and 1, got '1.5'");
    CHECK(criterion_error(head + "  P(t1 < 5 t3 < 4) > 0.5") == "c.crit:4:12: expected 'and' or ')' to close P(...), got 't3'");
    CHECK(criterion_error(head + "  t1 < 5 t3 < 4") == "c.crit:4:10: expected the end of the line after the constraint, got 't3'");
    CHECK(criterion_error(head + "  t1 5") == "c.crit:4:6: expected a comparison (<, <=, > or >=), got '5'");
    CHECK(criterion_error(head + "  t1 <") == "c.crit:4:7: expected a number, a name, '(' or '|', got the end of the input");
  }
}

TEST_SUITE("evaluation") {
  TEST_CASE("eq. (4): a deadline and a radius, jointly, with the caller's required probability") {
    const v::Criterion c = v::parse_criterion(kEq4, "eq4.crit");
    const auto verdict =
        v::evaluate_criterion(c, two_robots(), one_branch(robot(190, 36, 19.75, 18, 1.0), robot(0, 1, 0, 0, 1)), 0.8);
    REQUIRE(verdict.ok());
    const double expected = phi(10.0 / 6.0) * within_centred(2.0, 1.0);
    CHECK(verdict->name == "reach");
    CHECK(verdict->probability == doctest::Approx(expected).epsilon(1e-5));
    CHECK(verdict->required == doctest::Approx(0.8));
    CHECK(verdict->holds == (expected >= 0.8));
    CHECK(verdict->holds);
    CHECK(verdict->explanation.find("P(t1 <= 200 and |p - (19.75, 18)| < 2) = 0.8") == 0);
    // A stricter caller: the same probability, no longer enough.
    const auto strict =
        v::evaluate_criterion(c, two_robots(), one_branch(robot(190, 36, 19.75, 18, 1.0), robot(0, 1, 0, 0, 1)), 0.9);
    REQUIRE(strict.ok());
    CHECK_FALSE(strict->holds);
  }

  TEST_CASE("eq. (4) when robot1's early path ends near: its time and place together, not their product") {
    // Issue 13 item 7 (engine/time_position.hpp). robot1's last leg had two
    // equally likely NOISE paths: one fires 5 s early and rests on the
    // criterion's point, one fires 5 s late and rests 3 m off; the rest of
    // its finish time is N(200, 2.5^2). Exactly, P(t1 <= 200 and |p - x| < 2)
    // = 1/2 Phi(5 / 2.5) = 0.489 (only the early path is near); the
    // independence product says 1/2 x 1/2. At t = 200 the copula is exact.
    const v::Criterion c = v::parse_criterion(kEq4, "eq4.crit");
    v::RobotOutcome r1 = robot(200, 6.25 + 25.0, 19.75, 18, 1.0);
    r1.finish_time_s.components = {{0.5, 195.0, 6.25}, {0.5, 205.0, 6.25}};
    v::Gaussian2 near, far;
    near.mean = Eigen::Vector2d(19.75, 18);
    near.cov = 1e-4 * Eigen::Matrix2d::Identity();
    far.mean = Eigen::Vector2d(22.75, 18);
    far.cov = near.cov;
    r1.final_components = {near, far};
    r1.final_weights = {0.5, 0.5};
    r1.final_time_scores = {-1.0, 1.0};
    r1.time_score_correlation = 5.0 / std::sqrt(6.25 + 25.0);
    const auto coupled = v::evaluate_criterion(c, two_robots(), one_branch(r1, robot(0, 1, 0, 0, 1)), 0.4);
    REQUIRE(coupled.ok());
    CHECK(coupled->probability == doctest::Approx(0.5 * phi(2.0)).epsilon(1e-6));
    CHECK(coupled->holds);
    // Without the scores, the product (as before): 0.25, and the 0.4 fails.
    r1.final_time_scores.clear();
    r1.time_score_correlation = 0.0;
    const auto plain = v::evaluate_criterion(c, two_robots(), one_branch(r1, robot(0, 1, 0, 0, 1)), 0.4);
    REQUIRE(plain.ok());
    CHECK(plain->probability == doctest::Approx(0.25).epsilon(1e-6));
    CHECK_FALSE(plain->holds);
  }

  TEST_CASE("eq. (5): ordering and per-robot probability bounds") {
    const v::Criterion c = v::parse_criterion(kEq5, "eq5.crit");
    const auto verdict = v::evaluate_criterion(
        c, two_robots(), one_branch(robot(150, 25, 19.75, 18, 1.0), robot(190, 36, 20, 17.5, 2.25)), 0.5);
    REQUIRE(verdict.ok());
    const double bare = phi(50.0 / 5.0) * phi(10.0 / 6.0) * phi(40.0 / std::sqrt(61.0));
    const double p_near = within_centred(2.0, 1.0);   // 0.865 > 0.8
    const double q_near = within_centred(2.0, 2.25);  // 0.589, not > 0.8
    CHECK_FALSE(verdict->holds);
    // The verdict shows the group with the least margin: robot2's radius.
    CHECK(verdict->probability == doctest::Approx(q_near).epsilon(1e-5));
    CHECK(verdict->required == doctest::Approx(0.8));
    const std::string e = verdict->explanation;
    CHECK(e.find("P(t1 <= 200 and t3 <= 200 and t1 < t3) = 0.9522, holds (required >= 0.5); ") == 0);
    CHECK(e.find("P(|p - (19.75, 18)| < 2) = 0.8647, holds (required > 0.8)") != std::string::npos);
    CHECK(e.find("P(|q - (20, 17.5)| < 2) = 0.5889, fails (required > 0.8)") != std::string::npos);
    // With robot2 tighter, every group holds; the least margin is then the bare group's.
    const auto better = v::evaluate_criterion(
        c, two_robots(), one_branch(robot(150, 25, 19.75, 18, 1.0), robot(190, 36, 20, 17.5, 0.25)), 0.5);
    REQUIRE(better.ok());
    CHECK(better->holds);
    CHECK(better->probability == doctest::Approx(p_near).epsilon(1e-5));
    CHECK(bare > 0.5);
    // Ordering reversed: t1 < t3 fails, and the bare group with it. The
    // bare group is one event about two dependent conditions: t1 < t3 <= 200
    // implies t1 <= 200, so P = P(t1 < t3, t3 <= 200) <= P(t1 < t3) =
    // Phi(-45 / sqrt(61)), not that times Phi(1) (independence). (doctest's
    // Approx has an absolute scale of 1: compare such small numbers as ratios.)
    const auto late = v::evaluate_criterion(
        c, two_robots(), one_branch(robot(195, 25, 19.75, 18, 0.25), robot(150, 36, 20, 17.5, 0.25)), 0.5);
    REQUIRE(late.ok());
    CHECK_FALSE(late->holds);
    const double ordered = phi(-45.0 / std::sqrt(61.0));  // P(t3 > 200) ~ 4e-17 is below this ratio's precision
    CHECK(late->probability / ordered == doctest::Approx(1.0).epsilon(1e-3));
  }

  TEST_CASE("time events that share a robot's time are dependent: computed jointly, not as a product") {
    // t1 ~ N(195, 5^2), t3 ~ N(198, 6^2), independent. P(t1 <= 200 and t3 <=
    // 200 and t1 < t3): since t1 < t3 <= 200 implies t1 <= 200, it is
    // the integral over t3 <= 200 of the density of t3 times P(t1 < t3) =
    // Phi((t3 - 195) / 5), computed here by the trapezoid rule on a fine
    // grid. The independence product Phi(1) Phi(2/6) Phi(3/sqrt(61)) is
    // wrong by 0.043.
    const v::Criterion c = v::parse_criterion(kEq5, "eq5.crit");
    const auto verdict = v::evaluate_criterion(
        c, two_robots(), one_branch(robot(195, 25, 19.75, 18, 0.01), robot(198, 36, 20, 17.5, 0.01)), 0.5);
    REQUIRE(verdict.ok());
    double exact = 0.0;
    const double h = 0.001;
    for (double t3 = 198.0 - 60.0; t3 <= 200.0; t3 += h) {
      const double w = (t3 == 198.0 - 60.0 || t3 + h > 200.0) ? 0.5 : 1.0;
      exact += w * h * std::exp(-0.5 * (t3 - 198.0) * (t3 - 198.0) / 36.0) / (6.0 * std::sqrt(2.0 * M_PI)) *
               phi((t3 - 195.0) / 5.0);
    }
    const double product = phi(1.0) * phi(2.0 / 6.0) * phi(3.0 / std::sqrt(61.0));
    REQUIRE(std::abs(exact - product) > 0.04);
    // The explanation names the bare group first, with its probability.
    const std::string e = verdict->explanation;
    const std::size_t at = e.find("t1 < t3) = ");
    REQUIRE(at != std::string::npos);
    CHECK(std::stod(e.substr(at + 11)) == doctest::Approx(exact).epsilon(2e-4));
  }

  TEST_CASE("branches are weighted; pruned, blocked and unfinished mass count as failure") {
    const v::Criterion c = v::parse_criterion(
        "criterion deadline\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>)\nconstraints\n  t1 <= 200\n", "d.crit");
    v::SystemOutcome o;
    o.branches.push_back(branch(0.5, robot(190, 36, 0, 0, 1), robot(0, 1, 0, 0, 1)));
    o.branches.push_back(branch(0.3, robot(205, 16, 0, 0, 1), robot(0, 1, 0, 0, 1)));
    v::RobotOutcome stuck = robot(100, 1, 0, 0, 1);
    stuck.finished = false;
    o.branches.push_back(branch(0.15, stuck, robot(0, 1, 0, 0, 1)));
    o.pruned_mass = 0.05;
    const auto verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->probability == doctest::Approx(0.5 * phi(10.0 / 6.0) + 0.3 * phi(-5.0 / 4.0)).epsilon(1e-6));
    CHECK(verdict->explanation.find("pruned and blocked mass 0.05 counts as failure") != std::string::npos);
    // A robot the criterion does not name may be unfinished without harm.
    o.branches[2].robots[0].finished = true;
    o.branches[2].robots[1].finished = false;
    const auto other = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(other.ok());
    CHECK(other->probability == doctest::Approx(0.5 * phi(10.0 / 6.0) + 0.3 * phi(-5.0 / 4.0) + 0.15).epsilon(1e-6));
  }

  TEST_CASE("eq. (6): safety must hold at every moment at once: moments apart in time add up (Boole)") {
    // P(|p - q| > 1 at all times). Two samples that are not joined (a gap
    // between them) are separate stretches: nothing is assumed about how
    // their errors are related, so P(never close) >= 1 - the sum of P(close).
    // For a difference D ~ N(0, s^2 I), P(|D| <= r) = 1 - exp(-r^2 / (2 s^2)),
    // at r = 1.01: the separation is decided 1 % stricter (decided_separation()).
    const v::Criterion c = v::parse_criterion(kEq6, "eq6.crit");
    const double r = v::decided_separation(1.0, true, 0.0);
    CHECK(r == doctest::Approx(1.01));
    const auto close_at = [&](double s2) { return 1.0 - std::exp(-r * r / (2.0 * s2)); };
    v::SystemOutcome o = one_branch(robot(150, 25, 0, 0, 1.0), robot(160, 25, 0, 0, 1.0));
    v::SeparationSample close;
    close.robot_i = 1;  // either order of the pair
    close.robot_j = 0;
    close.time_s = 40;
    close.rigid_s = 20;
    close.difference.cov = 0.25 * Eigen::Matrix2d::Identity();
    v::SeparationSample wide = close;
    wide.robot_i = 0;
    wide.robot_j = 1;
    wide.time_s = 10;
    wide.difference.cov = 4.0 * Eigen::Matrix2d::Identity();
    o.branches[0].separations = {wide, close};
    auto verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    // 1 - 0.118 - 0.865 = 0.017 (the grid of the common error: about 1e-3).
    CHECK(verdict->probability == doctest::Approx(1.0 - close_at(4.0) - close_at(0.25)).epsilon(2e-3).scale(1.0));
    CHECK_FALSE(verdict->holds);
    o.branches[0].separations = {wide};
    verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->probability == doctest::Approx(1.0 - close_at(4.0)).epsilon(2e-3).scale(1.0));
    CHECK(verdict->holds);
    // Robots that never came within the horizon of each other: safe.
    o.branches[0].separations.clear();
    verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->holds);
    CHECK(verdict->probability == doctest::Approx(1.0).epsilon(1e-6));
  }

  TEST_CASE("eq. (6): a pass is one event: the path of the pair's difference with one error, not a sum over its moments") {
    // The difference drives along y = 1.5 from x = -20 to x = 20 in 10 s
    // (samples every second, joined), with the error D = m(t) + 0.5 z common
    // to the pass. It comes within d iff |1.5 + 0.5 z_y| < d somewhere on
    // the line: P = Phi((d - 1.5) / 0.5) - Phi((-d - 1.5) / 0.5), whatever
    // the number of samples. Boole over the 11 samples would count the pass
    // at x = 0 and its neighbours each once.
    const v::Criterion c = v::parse_criterion(kEq6, "eq6.crit");
    v::SystemOutcome o = one_branch(robot(150, 25, 0, 0, 1.0), robot(160, 25, 30, 0, 1.0));
    const auto pass = [&](double seconds, double rigid_s) {
      std::vector<v::SeparationSample> samples;
      for (int k = 0; k <= 10; ++k) {
        v::SeparationSample s;
        s.robot_i = 0;
        s.robot_j = 1;
        s.time_s = seconds * k / 10.0;
        s.difference.mean = Eigen::Vector2d(-20.0 + 4.0 * k, 1.5);
        s.difference.cov = 0.25 * Eigen::Matrix2d::Identity();
        s.joined = k > 0;
        s.rigid_s = rigid_s;
        samples.push_back(s);
      }
      return samples;
    };
    const double d = v::decided_separation(1.0, true, 0.0);  // 1.01 m: 1 % stricter
    const double exact = 1.0 - (phi((d - 1.5) / 0.5) - phi((-d - 1.5) / 0.5));
    o.branches[0].separations = pass(10.0, 20.0);
    auto verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->probability == doctest::Approx(exact).epsilon(2e-3).scale(1.0));
    // The same pass when the error is redrawn every second (a NOISE redrawn
    // within the leg): one stretch per second, added up: less, never more.
    o.branches[0].separations = pass(100.0, 1.0);
    verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->probability < exact - 0.05);
    // A required separation the samples cannot vouch for (they are kept only
    // within 6 m): refused, probability 0.
    const v::Criterion far = v::parse_criterion(
        "criterion far\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>) |\n        Delay<t3> ; (Delay<t4> # At<robot2, q>)\n"
        "constraints\n  t1, t3 > 0\n  P(|p - q| > 4.0) > 0.8\n",
        "far.crit");
    const auto refused = v::evaluate_criterion(far, two_robots(), o, 0.5);
    REQUIRE(refused.ok());
    CHECK(refused->probability == doctest::Approx(0.0));
    CHECK_FALSE(refused->holds);
  }

  TEST_CASE("eq. (6): a pass's answer is its own: far samples with wide errors in the same stretch change nothing") {
    // The pass of the case above (y = 1.5, error 0.5 z), preceded in the same
    // joined stretch by an approach from 60 m to 25 m away whose error is 2 z.
    // Those samples cannot come within d for any error on the grid (25 m -
    // 2 x 7.1), so the answer must be the pass's alone, to the bit: the
    // quadrature's refinement is set by the pieces that can decide it
    // (separation.cpp, StretchPath), not by the stretch's widest error.
    const auto sample = separation_sample;
    std::vector<v::SeparationSample> pass;
    for (int k = 0; k <= 10; ++k) pass.push_back(sample(10.0 + k, -20.0 + 4.0 * k, 1.5, 0.25, k > 0));
    std::vector<v::SeparationSample> approach;
    for (int k = 0; k < 8; ++k) approach.push_back(sample(5.5 + 0.5 * k, -60.0 + 5.0 * k, 1.5, 4.0, k > 0));
    for (v::SeparationSample s : pass) {
      s.joined = true;
      approach.push_back(s);
    }
    v::Branch alone = branch(1.0, robot(150, 25, 0, 0, 1.0), robot(160, 25, 30, 0, 1.0));
    alone.separations = pass;
    v::Branch after = alone;
    after.separations = approach;
    const double d = 1.01;
    const double exact = 1.0 - (phi((d - 1.5) / 0.5) - phi((-d - 1.5) / 0.5));
    const double p_alone = v::probability_always_apart(alone, 0, 1, d);
    CHECK(p_alone == doctest::Approx(exact).epsilon(2e-3).scale(1.0));
    CHECK(v::probability_always_apart(after, 0, 1, d) == p_alone);
    // Staying together: a sample that is within d for every error on the
    // grid (the pair 0.1 m apart, error 0.01 z) does not decide either.
    std::vector<v::SeparationSample> near;
    for (int k = 0; k <= 4; ++k) near.push_back(sample(k, 1.0, 0.0, 0.01, k > 0));
    v::Branch together = alone;
    together.separations = near;
    const double p_together = v::probability_always_within(together, 0, 1, 2.0);
    std::vector<v::SeparationSample> closer = near;
    for (int k = 5; k <= 8; ++k) closer.push_back(sample(k, 0.1, 0.0, 0.0001, true));
    together.separations = closer;
    CHECK(v::probability_always_within(together, 0, 1, 2.0) == p_together);
    CHECK(p_together == doctest::Approx(1.0).epsilon(1e-4));
  }

  TEST_CASE("eq. (6) for the team: branches that share a pair's stretches get the same number, others their own") {
    // probability_no_pair_within asks each distinct set of a pair's stretches
    // once per d (a six-robot mission has hundreds of branches that differ in
    // other robots' choices); the answer must be what each branch gives alone.
    const auto pass = [](double y, double var) {
      std::vector<v::SeparationSample> samples;
      for (int k = 0; k <= 10; ++k) samples.push_back(separation_sample(k, -20.0 + 4.0 * k, y, var, k > 0));
      return samples;
    };
    v::SystemOutcome o;
    o.branches.push_back(branch(0.3, robot(150, 25, 0, 0, 1.0), robot(160, 25, 30, 0, 1.0)));
    o.branches.push_back(o.branches[0]);
    o.branches.push_back(o.branches[0]);
    o.branches[0].separations = pass(1.5, 0.25);
    o.branches[1].separations = pass(1.2, 0.25);
    o.branches[2].separations = pass(1.5, 0.25);
    o.branches[1].weight = 0.4;
    const double d = 1.0;
    const double a0 = v::probability_always_apart(o.branches[0], 0, 1, d);
    const double a1 = v::probability_always_apart(o.branches[1], 0, 1, d);
    REQUIRE(a1 < a0 - 0.1);  // the closer pass is a different number
    CHECK(v::probability_no_pair_within(o, d) == doctest::Approx(0.3 * a0 + 0.4 * a1 + 0.3 * a0).epsilon(1e-12));
  }

  TEST_CASE("eq. (6) for the team over a curve of d: one pass gives each d's own answer, number for number") {
    // The cross-check asks a whole curve of d in one call (each pair's
    // stretches cut once, a branch no longer asked at a d where it already
    // counts nothing). Three robots, so pairs with no samples, a pair that
    // meets on every lap (Boole's sum passes 1 early: that branch counts 0
    // at the larger d), a d beyond what the samples vouch for and d = 0.
    const auto pass = [](double y, double var, double t0) {
      std::vector<v::SeparationSample> samples;
      for (int k = 0; k <= 10; ++k) samples.push_back(separation_sample(t0 + k, -20.0 + 4.0 * k, y, var, k > 0));
      return samples;
    };
    v::SystemOutcome o;
    v::Branch three = branch(0.5, robot(150, 25, 0, 0, 1.0), robot(160, 25, 30, 0, 1.0));
    three.robots.push_back(three.robots[1]);
    o.branches.assign(3, three);
    o.branches[0].separations = pass(1.5, 0.25, 0.0);
    for (int lap = 0; lap < 6; ++lap) {  // robots 0 and 2 pass each other six times, 0.6 m apart
      for (v::SeparationSample s : pass(0.6, 0.04, 100.0 * lap)) {
        s.robot_j = 2;
        if (s.time_s == 100.0 * lap) s.joined = false;
        o.branches[1].separations.push_back(s);
      }
    }
    o.branches[2].separations = pass(1.2, 0.25, 0.0);
    o.branches[1].weight = 0.3;
    o.branches[2].weight = 0.2;
    const std::vector<double> ds{0.0, 0.3, 0.55, 1.0, 1.4, 2.9, 3.5};
    const std::vector<double> together = v::probability_no_pair_within(o, ds);
    REQUIRE(together.size() == ds.size());
    for (std::size_t k = 0; k < ds.size(); ++k) {
      CAPTURE(ds[k]);
      // What each branch and pair gives alone (no shared stretches, no early stop).
      double expected = 0.0;
      for (const v::Branch& b : o.branches) {
        double close = 0.0;
        for (std::size_t i = 0; i < 3; ++i) {
          for (std::size_t j = i + 1; j < 3; ++j) close += 1.0 - v::probability_always_apart(b, i, j, ds[k]);
        }
        expected += b.weight * std::max(0.0, 1.0 - close);
      }
      CHECK(together[k] == expected);
      CHECK(v::probability_no_pair_within(o, ds[k]) == expected);
    }
    CHECK(together.front() == doctest::Approx(1.0));
    CHECK(together.back() == 0.0);  // beyond half of the horizon: not vouched for
    // At 1.0 the laps' branch is close for certain (six passes 0.6 m apart)
    // and counts nothing; the others keep their own pass's probability.
    CHECK(v::probability_always_apart(o.branches[1], 0, 2, 1.0) == 0.0);
    CHECK(together[3] == doctest::Approx(0.5 * v::probability_always_apart(o.branches[0], 0, 1, 1.0) +
                                         0.2 * v::probability_always_apart(o.branches[2], 0, 1, 1.0))
                             .epsilon(1e-12));
    CHECK(together[3] > 0.3);
  }

  TEST_CASE("eq. (6) for the team: the lightest branches, up to 1e-6 of the mass, count as failure unasked") {
    // A loop ends in many branches, nearly all of them very light (gen_7610:
    // 2,303 branches, 12 hold 0.99999): those summing to at most
    // kNegligibleBranchMass are not integrated and add nothing, so the team's
    // P(no pair within d) stays a lower bound, lower by at most that mass.
    const auto pass = [](double y) {
      std::vector<v::SeparationSample> samples;
      for (int k = 0; k <= 10; ++k) samples.push_back(separation_sample(k, -20.0 + 4.0 * k, y, 0.25, k > 0));
      return samples;
    };
    v::SystemOutcome o;
    o.branches.push_back(branch(1.0 - 3e-6, robot(150, 25, 0, 0, 1.0), robot(160, 25, 30, 0, 1.0)));
    o.branches[0].separations = pass(4.0);  // never near 1 m: P(apart) 1
    for (const double w : {4e-7, 5e-7, 2.1e-6}) {
      v::Branch light = o.branches[0];
      light.weight = w;
      light.separations = pass(4.0);
      o.branches.push_back(light);
    }
    const double d = 1.0;
    // Each branch alone: 1 less the grid's outside mass (beyond 5 sd, ~1e-6).
    const double a = v::probability_always_apart(o.branches[0], 0, 1, d);
    REQUIRE(a == doctest::Approx(1.0).epsilon(1e-5));
    REQUIRE(v::probability_always_apart(o.branches[1], 0, 1, d) == a);
    // 4e-7 + 5e-7 are unasked (0.9e-6); with 2.1e-6 they would pass 1e-6.
    const double p = v::probability_no_pair_within(o, d);
    CHECK(p == doctest::Approx((1.0 - 3e-6) * a + 2.1e-6 * a).epsilon(1e-15));
    CHECK(p < a * (1.0 - 0.8e-6));
    CHECK(p > a * (1.0 - 1.0e-6));
  }

  TEST_CASE("eq. (6) negated: together at all times is refused once the pair parts beyond the horizon") {
    const v::Criterion c = v::parse_criterion(
        "criterion together\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>) |\n        Delay<t3> ; (Delay<t4> # At<robot2, q>)\n"
        "constraints\n  t1, t3 > 0\n  P(|p - q| < 2.0) > 0.8\n",
        "together.crit");
    v::SystemOutcome o = one_branch(robot(150, 25, 0, 0, 1.0), robot(160, 25, 1, 0, 1.0));
    std::vector<v::SeparationSample> samples;
    for (int k = 0; k <= 4; ++k) {
      v::SeparationSample s;
      s.robot_i = 0;
      s.robot_j = 1;
      s.time_s = k;
      s.difference.mean = Eigen::Vector2d(1.0, 0.0);
      s.difference.cov = 0.01 * Eigen::Matrix2d::Identity();
      s.joined = k > 0;
      s.rigid_s = 20;
      samples.push_back(s);
    }
    o.branches[0].separations = samples;
    auto verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->probability == doctest::Approx(1.0).epsilon(1e-4));
    v::SeparationSample parted = samples.back();
    parted.time_s = 5;
    parted.difference.mean = Eigen::Vector2d(7.0, 0.0);
    parted.beyond_horizon = true;
    parted.joined = false;
    o.branches[0].separations.push_back(parted);
    verdict = v::evaluate_criterion(c, two_robots(), o, 0.5);
    REQUIRE(verdict.ok());
    CHECK(verdict->probability == doctest::Approx(0.0));
  }

  TEST_CASE("time forms: offsets, reversed sides, lower bounds") {
    const std::string head =
        "criterion t\nnetwork Delay<a> ; (Delay<w1> # At<robot1, p>) | Delay<b> ; (Delay<w2> # At<robot2, q>)\n"
        "constraints\n";
    const v::SystemOutcome o = one_branch(robot(100, 16, 0, 0, 1), robot(120, 9, 0, 0, 1));
    const auto prob = [&](const std::string& constraint) {
      const auto r = v::evaluate_criterion(v::parse_criterion(head + "  " + constraint + "\n", "t"), two_robots(), o, 0.5);
      REQUIRE(r.ok());
      return r->probability;
    };
    CHECK(prob("a + 10 < b") == doctest::Approx(phi(10.0 / 5.0)).epsilon(1e-6));
    CHECK(prob("b > a + 10") == doctest::Approx(phi(10.0 / 5.0)).epsilon(1e-6));
    CHECK(prob("a > b - 30") == doctest::Approx(phi(10.0 / 5.0)).epsilon(1e-6));
    CHECK(prob("110 >= a") == doctest::Approx(phi(10.0 / 4.0)).epsilon(1e-6));
    CHECK(prob("a >= 2 * 50 + 4") == doctest::Approx(1.0 - phi(1.0)).epsilon(1e-6));
    CHECK(prob("a, b <= 3 * 40") == doctest::Approx(phi(5.0) * phi(0.0)).epsilon(1e-6));
    CHECK(prob("|p - (3, 4)| > 0") == doctest::Approx(1.0).epsilon(1e-6));
  }

  TEST_CASE("the network decides what the variables are: At alone, any robot order") {
    const v::SystemOutcome o = one_branch(robot(100, 16, 0, 0, 1), robot(120, 9, 5, 5, 0.25));
    const auto near = v::evaluate_criterion(
        v::parse_criterion("criterion near\nnetwork At<robot2, q> | At<robot1, p>\nconstraints\n  |q - (5, 5)| < 1\n"
                           "  |p - (0, 0)| < 1\n", "n"),
        two_robots(), o, 0.3);
    REQUIRE(near.ok());
    CHECK(near->probability == doctest::Approx(within_centred(1, 0.25) * within_centred(1, 1)).epsilon(1e-5));
    // No constraints: the probability of reaching the network at all.
    v::SystemOutcome half = o;
    half.branches[0].weight = 0.6;
    const auto reach = v::evaluate_criterion(v::parse_criterion("criterion r\nnetwork At<robot1, p>\n", "r"), two_robots(), half, 0.5);
    REQUIRE(reach.ok());
    CHECK(reach->probability == doctest::Approx(0.6));
    CHECK(reach->holds);
    CHECK(reach->explanation == "P(the network is reached) = 0.6, holds (required >= 0.5)");
  }

  TEST_CASE("a criterion that does not fit the system is an error, never a silent 0") {
    const v::SystemOutcome o = one_branch(robot(100, 16, 0, 0, 1), robot(120, 9, 5, 5, 0.25));
    CHECK(evaluation_error("criterion x\nnetwork At<robot9, p>\n", o) ==
          "criterion 'x' (c.crit): unknown robot 'robot9' (the mission has robot1, robot2)");
    CHECK(evaluation_error("criterion x\nnetwork Delay<t1> ; At<robot1, p>\n", o) ==
          "criterion 'x' (c.crit) does not match the system's structure: 'Delay<W_robot1> # At<robot1, P_robot1>' "
          "and 'At<robot1, p>' differ: a '#' composition of 2 parts vs the process At. The system projected onto the "
          "criterion's processes is Delay<T_robot1> ; (Delay<W_robot1> # At<robot1, P_robot1>)");
    CHECK(evaluation_error("criterion x\nnetwork At<robot1, p> # At<robot2, q>\n", o).find(
              "differ: a '|' composition of 2 parts vs a '#' composition of 2 parts") != std::string::npos);
    CHECK(evaluation_error("criterion x\nnetwork At<robot1, p> | At<robot1, q>\n", o).find(
              "differ: the process At vs a '|' composition of 2 parts") != std::string::npos);
    CHECK(evaluation_error("criterion x\nnetwork Delay<t>\n", o) ==
          "criterion 'x' (c.crit) names no robot: its network needs At<robot, position> for each robot it constrains");
    CHECK(evaluation_error("criterion x\nnetwork Delay<t1> ; (Delay<t2> # At<robot1, p>)\nconstraints\n  t2 < 5\n", o) ==
          "criterion 'x' (c.crit): 't2' is how long robot1 stays at its final position (the Delay beside its At); the "
          "verifier does not give its distribution, so it cannot be constrained");
    v::SystemOutcome wrong = o;
    wrong.branches[0].robots.pop_back();
    CHECK(evaluation_error("criterion x\nnetwork At<robot1, p>\n", wrong) ==
          "criterion 'x' (c.crit): the outcome has 1 robots in a branch, the mission 2");
  }

  TEST_CASE("eq. (7): the success criterion of a mission") {
    const v::Criterion c = v::success_criterion(two_robots(), 200, 2.0);
    CHECK(c.name == "success");
    CHECK(v::pars::to_string(c.network) ==
          "Delay<t_robot1> ; (Delay<w_robot1> # At<robot1, p_robot1>) | "
          "Delay<t_robot2> ; (Delay<w_robot2> # At<robot2, p_robot2>)");
    REQUIRE(c.constraints.size() == 3);
    CHECK(v::to_string(c.constraints[0]) == "t_robot1, t_robot2 <= 200");
    CHECK(v::to_string(c.constraints[1]) == "|p_robot1 - (19.75, 18)| <= 2");
    CHECK(v::to_string(c.constraints[2]) == "|p_robot2 - (20, 17.5)| <= 2");
    CHECK(v::parse_criterion(v::to_string(c), "success.crit") == c);
    const auto verdict = v::evaluate_criterion(
        c, two_robots(), one_branch(robot(180, 25, 19.75, 18, 0.5), robot(195, 9, 20, 17.5, 0.5)), 0.8);
    REQUIRE(verdict.ok());
    const double expected = phi(20.0 / 5.0) * phi(5.0 / 3.0) * within_centred(2, 0.5) * within_centred(2, 0.5);
    CHECK(verdict->probability == doctest::Approx(expected).epsilon(1e-5));
    CHECK(verdict->holds == (expected >= 0.8));
  }
}
