#pragma once
/// Performance criteria G(P, C) (the seed paper's Defs. 2-7, eqs. 4-6): a PARS
/// network P of Delay and At processes plus constraints C on its variables,
/// read from a criterion file (docs/pars.md, "Criterion files"), e.g.
///
///   criterion ordered_arrival
///   network Delay<t1> ; (Delay<t2> # At<robot1, p>) | Delay<t3> ; (Delay<t4> # At<robot2, q>)
///   constraints
///     t1, t3 <= 200
///     t1 < t3
///     P(|p - (19.75, 18)| < 2) > 0.8
///
/// Evaluation projects the system onto the criterion's processes, checks
/// structural equivalence (Def. 7), binds the variables to the system's random
/// variables and computes the constraints' probability on the final state.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/located_error.hpp"
#include "p3at/common/result.hpp"
#include "p3at/mission/mission.hpp"
#include "p3at/verifier/outcome.hpp"
#include "p3at/verifier/pars/expr.hpp"
#include "p3at/verifier/pars/term.hpp"
#include "p3at/verifier/verify.hpp"

namespace p3at::verifier {

/// One comparison as written: `t1 <= 200`, `t1, t3 <= 200` (each variable),
/// `t1 + 10 < t3`, `|p - (19.75, 18)| < 2`, `|p - q| > 1`.
struct Comparison {
  std::vector<pars::Expr> left;      ///< one expression, or two or more variables
  pars::CompareOp op = pars::CompareOp::less;
  pars::Expr right;
  int line = 0;                      ///< where it starts in its file (not compared)
  int column = 0;
  bool operator==(const Comparison& other) const { return left == other.left && op == other.op && right == other.right; }
};

/// One line of the constraints: a bare comparison (all bare ones must hold
/// together, with the caller's required probability), or P(e1 and e2 ...) > x
/// (its own required probability; >= allowed too).
struct Constraint {
  std::vector<Comparison> events;    ///< one for a bare constraint
  bool probabilistic = false;
  pars::CompareOp bound_op = pars::CompareOp::greater;   ///< greater or greater_equal
  double bound = 0.0;                ///< in [0, 1]
  int line = 0;                      ///< not compared
  int column = 0;
  bool operator==(const Constraint& other) const {
    return events == other.events && probabilistic == other.probabilistic && bound_op == other.bound_op &&
           bound == other.bound;
  }
};

struct Criterion {
  std::string name;
  std::string source;                ///< the file it came from, for messages (not compared)
  pars::Term network;
  std::vector<Constraint> constraints;
  bool operator==(const Criterion& other) const {
    return name == other.name && network == other.network && constraints == other.constraints;
  }
};

/// A criterion file that cannot be read: what() is "file:line:column: detail"
/// ("file: detail" without a position), like mission::MissionError.
class CriterionError : public LocatedError {
 public:
  using LocatedError::LocatedError;
};

/// Parses and checks a criterion (syntax, processes, variables, the form of
/// every constraint). Throws CriterionError at the first problem.
Criterion parse_criterion(std::string_view text, const std::string& source_name);
/// Reads the file at `path` and parses it (errors without a position when unreadable).
Criterion load_criterion_file(const std::string& path);
/// The criterion as a file: parse_criterion(to_string(c)) == c.
std::string to_string(const Criterion& criterion);
/// A constraint as written in a file, e.g. "P(|p - (1, 2)| < 2) > 0.8".
std::string to_string(const Constraint& constraint);

/// Evaluates `criterion` on the system's final distribution. The system is
/// projected onto the criterion's processes: each robot named by an At is
///   Delay<T> ; (Delay<W> # At<robot, P>)
/// with T its finish time, W its wait at the end, P its true final position.
/// The projection must be structurally equivalent to the network (Def. 7);
/// matching binds the criterion's variables to T, W and P. Within a branch the
/// robots' variables are treated as independent: each constraint group's
/// probability is the product of its comparisons' probabilities, summed over
/// the branches by weight (pruned and blocked mass count as failure; so does a
/// branch where a robot of the criterion never finishes). A distance between
/// two robots' positions must hold at every moment (eq. 6): its probability
/// is separation.hpp's lower bound over the pair's positions at the same
/// times along the branch. Bare constraints
/// form one group that must reach `default_required_probability`; each
/// P(...) > x its own. The verdict reports the group with the least margin
/// and holds when every group holds. An Error explains a criterion that does
/// not fit the system (unknown robot, wrong composition, unbindable variable).
///
/// `separation_step_m`: a separation is decided as the gate decides Rmax
/// (separation.hpp, decided_separation()): "never within d" at d 1 % larger
/// and at least this much larger, "always within d" as much smaller (verify
/// passes the distance two robots close in one cycle at their top speeds;
/// 0 decides at d itself).
Result<CriterionVerdict> evaluate_criterion(const Criterion& criterion, const mission::Mission& mission,
                                            const SystemOutcome& outcome, double default_required_probability,
                                            double separation_step_m = 0.0);

/// The paper's eq. (7) as a criterion: every robot finishes by tmax_s and ends
/// within rmax_m of its goal, all together (no probability bound: the caller's
/// threshold applies).
Criterion success_criterion(const mission::Mission& mission, double tmax_s, double rmax_m);

}  // namespace p3at::verifier
