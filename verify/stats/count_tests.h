// Tests on counts: the exact binomial test, the multinomial test (Pearson chi-square with pooling),
// and a test that a sample of integer counts follows Binomial(n, p).
#pragma once

#include <cstdint>
#include <span>

#include "verify/stats/chi_square.h"

namespace glintlab::verify {

struct BinomialTestResult {
  double p_value = 1;      // two-sided
  double estimate = 0;     // successes / trials
  std::uint64_t successes = 0, trials = 0;
  double p0 = 0;           // the null success probability
};

// Exact two-sided binomial test of `successes` in `trials` against success probability p0: the
// probability of every outcome no more likely than the observed one (the "minimum likelihood"
// definition, with a relative tolerance of 1e-7 on the comparison, as R's binom.test). Each tail is
// found by bisection on the unimodal pmf and summed by Boost's binomial CDF: O(log n).
BinomialTestResult binomial_test(std::uint64_t successes, std::uint64_t trials, double p0);

// Multinomial goodness of fit: counts against probabilities (normalised by their sum here),
// Pearson's X² over pooled cells (pool_bins, cells with E < min_expected merged in index order),
// dof = cells − 1. A count in a cell of probability exactly 0 is a hard failure (p = 0).
PearsonResult multinomial_test(std::span<const std::int64_t> counts,
                               std::span<const double> probabilities, double min_expected = 5);

// Whether the values (each a count in 0..trials) follow Binomial(trials, p): the values'
// histogram against M·pmf over the count values, the far tails (beyond np ± (10σ + 10)) lumped in
// one cell each, then pooled as above (so both tails merge until E ≥ min_expected);
// dof = cells − 1. A value above `trials` is a hard failure.
PearsonResult binomial_counts_test(std::span<const std::uint64_t> values, std::uint64_t trials,
                                   double p, double min_expected = 5);

}  // namespace glintlab::verify
