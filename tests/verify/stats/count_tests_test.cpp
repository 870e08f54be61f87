// Exact binomial, multinomial and binomial-counts tests against known answers.
#include "verify/stats/count_tests.h"

#include <gtest/gtest.h>

#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <vector>

#include "verify/stats/stats_test_samplers.h"

namespace glintlab::verify {
namespace {

// Brute force: the total probability of outcomes no more likely than k.
double brute_binomial_p(std::uint64_t k, std::uint64_t n, double p) {
  const boost::math::binomial_distribution<double> d(double(n), p);
  const double dk = boost::math::pdf(d, double(k)) * (1 + 1e-7);
  double s = 0;
  for (std::uint64_t i = 0; i <= n; ++i)
    if (boost::math::pdf(d, double(i)) <= dk) s += boost::math::pdf(d, double(i));
  return std::min(1.0, s);
}

TEST(BinomialTest, PublishedValues) {
  // R: binom.test(c(682, 243), p = 3/4) → p-value = 0.3825 (Mendel's peas).
  EXPECT_NEAR(binomial_test(682, 925, 0.75).p_value, 0.3825, 5e-5);
  // Symmetric: 2·P(X ≤ 7 | 20, ½) = 2·137980/2^20.
  EXPECT_NEAR(binomial_test(7, 20, 0.5).p_value, 2 * 137980.0 / 1048576.0, 1e-14);
  EXPECT_NEAR(binomial_test(13, 20, 0.5).p_value, 2 * 137980.0 / 1048576.0, 1e-14);
  // Asymmetric, by hand: n = 10, p = 0.3, k = 6: pmf(0) + P(X ≥ 6) = 0.0282475249 + 0.0473489874.
  EXPECT_NEAR(binomial_test(6, 10, 0.3).p_value, 0.0755965123, 1e-9);
  EXPECT_EQ(binomial_test(3, 10, 0.5).p_value, binomial_test(7, 10, 0.5).p_value);
  EXPECT_EQ(binomial_test(5, 10, 0.5).p_value, 1.0);
  EXPECT_EQ(binomial_test(0, 10, 0.0).p_value, 1.0);
  EXPECT_EQ(binomial_test(1, 10, 0.0).p_value, 0.0);
}

TEST(BinomialTest, MatchesBruteForce) {
  for (std::uint64_t n : {1u, 2u, 7u, 30u, 101u, 500u})
    for (double p : {0.01, 0.2, 0.5, 0.77})
      for (std::uint64_t k = 0; k <= n; k += std::max<std::uint64_t>(1, n / 13)) {
        const double want = brute_binomial_p(k, n, p);
        EXPECT_NEAR(binomial_test(k, n, p).p_value, want, 1e-12 + 1e-9 * want)
            << "k=" << k << " n=" << n << " p=" << p;
      }
  // Large n in O(log n): 1e9 trials, 1.0001× the expected successes (z ≈ 3.16).
  const BinomialTestResult r = binomial_test(500'050'000, 1'000'000'000, 0.5);
  EXPECT_NEAR(r.p_value, std::erfc(50000.0 / std::sqrt(2 * 2.5e8)), 2e-5);
}

// Mendel's dihybrid cross: 315, 108, 101, 32 against 9:3:3:1 → X² = 0.470024, dof 3, p = 0.9254.
TEST(MultinomialTest, Mendel) {
  const std::vector<std::int64_t> counts{315, 108, 101, 32};
  const std::vector<double> probs{9, 3, 3, 1};  // normalised inside
  const PearsonResult r = multinomial_test(counts, probs);
  EXPECT_NEAR(r.statistic, 0.470024, 1e-6);
  EXPECT_EQ(r.dof, 3);
  // P(χ²₃ > x) = erfc(√(x/2)) + √(2x/π) e^{−x/2}.
  const double x = r.statistic;
  EXPECT_NEAR(r.p_value, std::erfc(std::sqrt(x / 2)) + std::sqrt(2 * x / testing::kPi) * std::exp(-x / 2), 1e-12);
  EXPECT_NEAR(r.p_value, 0.9254, 1e-4);
}

TEST(MultinomialTest, PoolingAndZeroCells) {
  // Expected 2, 2, 2, 50, 44: the first three pool into one cell of 6 → 3 cells, dof 2.
  const std::vector<double> probs{0.02, 0.02, 0.02, 0.5, 0.44};
  const std::vector<std::int64_t> counts{1, 3, 2, 52, 42};
  const PearsonResult r = multinomial_test(counts, probs);
  EXPECT_EQ(r.cells, 3u);
  EXPECT_EQ(r.dof, 2);
  const double want = 0.0 / 6 + 4.0 / 50 + 4.0 / 44;
  EXPECT_NEAR(r.statistic, want, 1e-14);
  EXPECT_NEAR(r.p_value, std::exp(-want / 2), 1e-14);  // P(χ²₂ > x) = e^{−x/2}
  // A count where the probability is exactly 0 fails hard.
  const std::vector<double> probs0{0.5, 0.0, 0.5};
  const std::vector<std::int64_t> counts0{50, 1, 49};
  const PearsonResult z = multinomial_test(counts0, probs0);
  EXPECT_TRUE(z.hard_fail);
  EXPECT_EQ(z.p_value, 0.0);
}

TEST(BinomialCountsTest, HandExample) {
  // Binomial(2, ½): pmf ¼, ½, ¼. 40 values: 8 zeros, 22 ones, 10 twos. E = 10, 20, 10.
  std::vector<std::uint64_t> v;
  v.insert(v.end(), 8, 0);
  v.insert(v.end(), 22, 1);
  v.insert(v.end(), 10, 2);
  const PearsonResult r = binomial_counts_test(v, 2, 0.5);
  EXPECT_EQ(r.cells, 3u);
  EXPECT_NEAR(r.statistic, 4.0 / 10 + 4.0 / 20 + 0.0, 1e-14);
  EXPECT_NEAR(r.p_value, std::exp(-r.statistic / 2), 1e-14);
  v.push_back(3);  // outside the support
  EXPECT_TRUE(binomial_counts_test(v, 2, 0.5).hard_fail);
}

// Counts of successes among 200 Bernoulli(0.3) trials, 5000 times: accepted for p = 0.3,
// rejected for p = 0.31.
TEST(BinomialCountsTest, SimulatedCounts) {
  std::vector<std::uint64_t> v(5000);
  for (std::uint64_t s = 0; s < v.size(); ++s) {
    std::uint64_t k = 0;
    for (std::uint64_t t = 0; t < 200; ++t) k += testing::uniform(77, s * 200 + t, 0) < 0.3 ? 1 : 0;
    v[s] = k;
  }
  const PearsonResult ok = binomial_counts_test(v, 200, 0.3);
  const PearsonResult bad = binomial_counts_test(v, 200, 0.31);
  EXPECT_GT(ok.p_value, 1e-3) << ok.statistic << " dof " << ok.dof;
  EXPECT_LT(bad.p_value, 1e-6) << bad.statistic << " dof " << bad.dof;
  std::cout << "Binomial(200, 0.3) counts: p=" << ok.p_value << " (" << ok.cells
            << " cells); against p = 0.31: p=" << bad.p_value << "\n";
}

}  // namespace
}  // namespace glintlab::verify
