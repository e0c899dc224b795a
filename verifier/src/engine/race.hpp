#pragma once
/// Which of several independent times comes first (issue 13 item 6: three or
/// more robots racing).

#include <vector>

#include "p3at/verifier/mog.hpp"

namespace p3at::verifier::engine {

/// P(X_c is the smallest) for independent X_0..X_n-1, each c: the integral of
/// X_c's density times every other's survival, by a deterministic sum over a
/// grid of the plausible span (CDF differences, so point masses count; point
/// masses that tie within a cell share it evenly: the times are different
/// robots', and the tie an artifact of identical quadrature nodes). Products
/// of pairwise probabilities
/// P(X_c < X_o) are not this for three or more: the events X_c < X_o are
/// positively correlated through X_c (three equal times give 1/4 each by the
/// product, 1/3 in truth).
/// Empty input gives an empty result; the probabilities sum to 1 up to the
/// grid's resolution (1,000 cells over the plausible span).
std::vector<double> first_probabilities(const std::vector<const Mixture1*>& xs);

}  // namespace p3at::verifier::engine
