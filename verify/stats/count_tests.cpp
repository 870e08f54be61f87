// Exact binomial, multinomial and binomial-counts tests; see count_tests.h.
#include "verify/stats/count_tests.h"

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace glintlab::verify {

BinomialTestResult binomial_test(std::uint64_t k, std::uint64_t n, double p0) {
  BinomialTestResult r;
  r.successes = k;
  r.trials = n;
  r.p0 = p0;
  if (n == 0) return r;
  r.estimate = double(k) / double(n);
  if (k > n || !(p0 >= 0 && p0 <= 1)) {
    r.p_value = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  if (p0 == 0) {
    r.p_value = k == 0 ? 1.0 : 0.0;
    return r;
  }
  if (p0 == 1) {
    r.p_value = k == n ? 1.0 : 0.0;
    return r;
  }
  const boost::math::binomial_distribution<double> dist(double(n), p0);
  auto pmf = [&](std::uint64_t i) { return boost::math::pdf(dist, double(i)); };
  auto cdf = [&](std::uint64_t i) { return boost::math::cdf(dist, double(i)); };         // P(X ≤ i)
  auto above = [&](std::uint64_t i) {                                                      // P(X > i)
    return boost::math::cdf(boost::math::complement(dist, double(i)));
  };
  const double d = pmf(k) * (1 + 1e-7);
  const double m = double(n) * p0;
  if (double(k) == m) {
    r.p_value = 1;
    return r;
  }
  double p = 0;
  if (double(k) < m) {
    // Upper side [⌈m⌉, n], where the pmf does not increase: the first i with pmf(i) ≤ d.
    std::uint64_t lo = static_cast<std::uint64_t>(std::ceil(m)), hi = n + 1;
    while (lo < hi) {
      const std::uint64_t mid = lo + (hi - lo) / 2;
      if (pmf(mid) <= d) hi = mid; else lo = mid + 1;
    }
    p = cdf(k) + (lo <= n ? (lo == 0 ? 1.0 : above(lo - 1)) : 0.0);
  } else {
    // Lower side [0, ⌊m⌋], where the pmf does not decrease: the last i with pmf(i) ≤ d.
    std::uint64_t lo = 0, hi = static_cast<std::uint64_t>(std::floor(m)) + 1;  // first i with pmf > d
    while (lo < hi) {
      const std::uint64_t mid = lo + (hi - lo) / 2;
      if (pmf(mid) > d) hi = mid; else lo = mid + 1;
    }
    p = (lo > 0 ? cdf(lo - 1) : 0.0) + above(k - 1);
  }
  r.p_value = std::min(1.0, p);
  return r;
}

PearsonResult multinomial_test(std::span<const std::int64_t> counts,
                               std::span<const double> probabilities, double min_expected) {
  double total = 0, psum = 0;
  for (std::int64_t c : counts) total += double(c);
  for (double q : probabilities) psum += q;
  std::vector<double> expected(probabilities.size());
  for (std::size_t i = 0; i < expected.size(); ++i) expected[i] = psum > 0 ? total * probabilities[i] / psum : 0.0;
  return pearson_chi_square(counts, expected, min_expected, 1);
}

PearsonResult binomial_counts_test(std::span<const std::uint64_t> values, std::uint64_t trials,
                                   double p, double min_expected) {
  const double M = double(values.size());
  const double mean = double(trials) * p, sd = std::sqrt(double(trials) * p * (1 - p));
  const double lo_d = std::max(0.0, std::floor(mean - 10 * sd - 10));
  const double hi_d = std::min(double(trials), std::ceil(mean + 10 * sd + 10));
  const auto lo = static_cast<std::uint64_t>(lo_d), hi = static_cast<std::uint64_t>(hi_d);
  // Cells: [0, lo) lumped, lo..hi one each, (hi, trials] lumped, then "above trials" (E = 0).
  const std::size_t inner = static_cast<std::size_t>(hi - lo + 1);
  std::vector<double> expected(inner + 3, 0.0);
  std::vector<std::int64_t> observed(inner + 3, 0);
  const boost::math::binomial_distribution<double> dist(double(trials), p);
  if (lo > 0) expected[0] = M * boost::math::cdf(dist, double(lo - 1));
  for (std::size_t i = 0; i < inner; ++i) expected[i + 1] = M * boost::math::pdf(dist, double(lo + i));
  if (hi < trials) expected[inner + 1] = M * boost::math::cdf(boost::math::complement(dist, double(hi)));
  for (std::uint64_t v : values) {
    std::size_t c;
    if (v > trials) c = inner + 2;
    else if (v < lo) c = 0;
    else if (v > hi) c = inner + 1;
    else c = static_cast<std::size_t>(v - lo) + 1;
    ++observed[c];
  }
  return pearson_chi_square(observed, expected, min_expected, 1);
}

}  // namespace glintlab::verify
