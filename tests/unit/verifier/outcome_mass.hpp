#pragma once
// The probability mass an evaluation accounts for: the branches' weights plus
// every mass it reports as lost (pruned, blocked, loops cut off, work budget
// run out). The verifier's tests check it sums to 1: no mass silently dropped.

#include "p3at/verifier/outcome.hpp"

namespace p3at::verifier::test {

inline double accounted_mass(const SystemOutcome& o) {
  double w = o.pruned_mass + o.blocked_mass + o.loop_cutoff_mass + o.work_cutoff_mass;
  for (const Branch& b : o.branches) w += b.weight;
  return w;
}

}  // namespace p3at::verifier::test
