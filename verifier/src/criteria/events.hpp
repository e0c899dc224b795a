#pragma once
// What a criterion's comparisons mean: each is classified once, when the file
// is read (so a form the evaluator cannot compute is a located parse error),
// and again when it is evaluated.

#include <map>
#include <string>
#include <vector>

#include "p3at/verifier/criteria.hpp"

namespace p3at::verifier::detail {

enum class VariableKind { time, position };

/// The network's variables: Delay<t> gives a time, At<robot, p> a position.
using VariableKinds = std::map<std::string, VariableKind>;

/// One probability to compute.
struct Event {
  enum class Kind {
    time_bound,         ///< a + offset OP value
    time_order,         ///< a + offset OP b
    distance_to_point,  ///< |a - (x, y)| OP value
    distance_between,   ///< |a - b| OP value
  };
  Kind kind = Kind::time_bound;
  std::string a;
  std::string b;
  double offset = 0.0;
  pars::CompareOp op = pars::CompareOp::less;   ///< less, less_equal, greater or greater_equal
  double value = 0.0;
  double x = 0.0;
  double y = 0.0;
};

/// The events of one comparison (one per variable of a list). On failure,
/// returns false with `problem` saying what was expected.
bool classify(const Comparison& comparison, const VariableKinds& kinds, std::vector<Event>& events,
              std::string& problem);

/// True for the comparisons "less than" (< and <=; equal for continuous variables).
bool is_less(pars::CompareOp op);

}  // namespace p3at::verifier::detail
