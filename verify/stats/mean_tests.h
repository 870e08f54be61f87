// Tests of a mean: one-sample z and t tests against a known value, and Welch's two-sample t test,
// from moment accumulators that reduce deterministically in parallel.
#pragma once

#include <cstdint>
#include <functional>

namespace glintlab::verify {

// Count, mean and sum of squared deviations (Welford), merged with Chan et al.'s pairwise update.
// Merging is not associative in floating point, so parallel code merges fixed chunks in chunk order
// (accumulate_mean does): the result then does not depend on the thread count.
struct MeanAccumulator {
  std::uint64_t n = 0;
  double mean = 0;
  double m2 = 0;  // Σ (x − mean)²

  void add(double x);
  void merge(const MeanAccumulator& o);
  double variance() const;  // sample variance m2 / (n − 1); 0 when n < 2
  double sum() const { return mean * static_cast<double>(n); }

  // From plain sums (Σx, Σx²): loses precision when the mean is large against the spread, so
  // prefer add/merge; provided for callers that already hold the sums.
  static MeanAccumulator from_sums(std::uint64_t n, double sum, double sum_of_squares);
};

// f(0), …, f(n − 1) accumulated in parallel (TBB) over fixed chunks of `chunk` indices, merged in
// chunk order: bit-identical for any thread count.
MeanAccumulator accumulate_mean(const std::function<double(std::uint64_t)>& f, std::uint64_t n,
                                std::uint64_t chunk = 4096);

struct MeanTestResult {
  double statistic = 0;  // z or t
  double dof = 0;        // degrees of freedom (infinity for the z test)
  double p_value = 1;    // two-sided
  double estimate = 0;   // the mean (or difference of means)
  double std_error = 0;  // standard error of the estimate
};

// z test of mean = mu0 with known standard deviation sigma of one observation (normal p-value).
MeanTestResult z_test(const MeanAccumulator& a, double mu0, double sigma);
// z test with the sample standard deviation (large-n approximation, normal p-value).
MeanTestResult z_test(const MeanAccumulator& a, double mu0);
// Student t test of mean = mu0 (dof n − 1). Needs n ≥ 2.
MeanTestResult t_test(const MeanAccumulator& a, double mu0);
// Welch's two-sample t test of equal means (Welch–Satterthwaite dof). Needs n ≥ 2 in each.
//
// Degenerate cases: with zero standard error the statistic is 0 and p = 1 when the means agree
// exactly, ±infinity and p = 0 otherwise; with too few observations p is NaN.
MeanTestResult welch_t_test(const MeanAccumulator& a, const MeanAccumulator& b);

// Quantiles for confidence intervals: the standard normal's and Student t's (dof > 0) inverse
// cdf at probability p in (0, 1).
double normal_quantile(double p);
double student_t_quantile(double p, double dof);

}  // namespace glintlab::verify
