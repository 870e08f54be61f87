// Kolmogorov–Smirnov statistic and distribution against known values.
#include "verify/stats/ks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "verify/stats/stats_test_samplers.h"

namespace glintlab::verify {
namespace {

// Quantiles of the limiting Kolmogorov distribution (the classical table): K_{0.90} = 1.2238,
// K_{0.95} = 1.3581, K_{0.99} = 1.6276.
TEST(Kolmogorov, LimitingQuantiles) {
  EXPECT_NEAR(kolmogorov_sf(1.2238), 0.10, 2e-4);
  EXPECT_NEAR(kolmogorov_sf(1.3581), 0.05, 1e-4);
  EXPECT_NEAR(kolmogorov_sf(1.6276), 0.01, 2e-5);
  // The two series agree where they meet, and the CDF is a CDF.
  EXPECT_NEAR(kolmogorov_cdf(1 - 1e-12), kolmogorov_cdf(1 + 1e-12), 1e-11);
  EXPECT_EQ(kolmogorov_cdf(0.0), 0.0);
  // Deep lower tail: the first theta term, √(2π)/x·e^{−π²/(8x²)} = 5.0504e-13 at x = 0.2.
  EXPECT_NEAR(kolmogorov_cdf(0.2) / (std::sqrt(2 * 3.141592653589793) / 0.2 *
                                     std::exp(-3.141592653589793 * 3.141592653589793 / 0.32)),
              1.0, 1e-12);
  EXPECT_NEAR(kolmogorov_sf(5.0), 2 * std::exp(-50.0), 1e-30);  // first term dominates
  EXPECT_NEAR(kolmogorov_cdf(0.5), 1 - kolmogorov_sf(0.5), 1e-15);
  double prev = 0;
  for (double x = 0.1; x < 3; x += 0.05) {
    const double c = kolmogorov_cdf(x);
    EXPECT_GE(c, prev);
    prev = c;
  }
}

// Exact finite-n distribution against closed forms: P(D_n < d) = n!(2d − 1/n)^n for
// 1/(2n) ≤ d ≤ 1/n, P(D_n ≥ d) = 2(1 − d)^n for 1 − 1/n ≤ d ≤ 1, and P(D_1 < d) = 2d − 1.
TEST(Kolmogorov, ExactClosedForms) {
  EXPECT_NEAR(ks_cdf_exact(0.15, 5), 120 * std::pow(0.1, 5), 1e-15);
  EXPECT_NEAR(ks_cdf_exact(0.18, 5), 120 * std::pow(0.16, 5), 1e-14);
  EXPECT_NEAR(1 - ks_cdf_exact(0.9, 5), 2 * std::pow(0.1, 5), 1e-13);
  EXPECT_NEAR(1 - ks_cdf_exact(0.85, 6), 2 * std::pow(0.15, 6), 1e-13);
  EXPECT_NEAR(ks_cdf_exact(0.7, 1), 0.4, 1e-15);
  EXPECT_EQ(ks_cdf_exact(0.05, 10), 0.0);
  EXPECT_EQ(ks_cdf_exact(1.0, 10), 1.0);
}

// Two-sided critical values of D_n (Massey 1951 / Miller 1956 tables): P(D_n ≥ d) = α.
TEST(Kolmogorov, ExactCriticalValues) {
  EXPECT_NEAR(ks_sf(0.56328, 5), 0.05, 2e-4);
  EXPECT_NEAR(ks_sf(0.40925, 10), 0.05, 2e-4);
  EXPECT_NEAR(ks_sf(0.48893, 10), 0.01, 1e-4);
  EXPECT_NEAR(ks_sf(0.29408, 20), 0.05, 2e-4);
  // The corrected asymptotic form is close at n = 10 already (the uncorrected one gives 0.070).
  EXPECT_NEAR(ks_sf_asymptotic(0.40925, 10), 0.05, 2e-3);
  EXPECT_NEAR(kolmogorov_sf(std::sqrt(10.0) * 0.40925), 0.0702, 1e-4);
}

// Where ks_sf switches to the asymptotic form (matrix order > 121, i.e. ⌊n·d⌋ ≥ 61), it is
// within 1e-4 of the exact value.
TEST(Kolmogorov, AsymptoticBranchAccuracy) {
  for (std::size_t n : {70u, 100u, 400u, 1000u, 1500u, 4000u}) {
    for (double x : {0.97, 1.36, 1.63, 2.0, 3.0}) {
      const double d = x / std::sqrt(double(n));
      const double m = 2 * std::floor(double(n) * d) + 1;
      if (m <= double(kKsExactMaxOrder) || m > 201) continue;
      const double exact = 1 - ks_cdf_exact(d, n);
      EXPECT_NEAR(ks_sf_asymptotic(d, n), exact, 1e-4) << "n=" << n << " d=" << d;
      EXPECT_EQ(ks_sf(d, n), ks_sf_asymptotic(d, n));
    }
  }
}

TEST(KsTest, HandExample) {
  // Samples 0.1, 0.4, 0.7 against Uniform[0, 1]: D+ = max(1/3 − 0.1, 2/3 − 0.4, 1 − 0.7) = 0.3,
  // D− = max(0.1, 0.4 − 1/3, 0.7 − 2/3) = 0.1.
  const std::vector<double> x{0.7, 0.1, 0.4};
  const KsResult r = ks_test_uniform(x);
  EXPECT_NEAR(r.d_plus, 0.3, 1e-15);
  EXPECT_NEAR(r.d_minus, 0.1, 1e-15);
  EXPECT_NEAR(r.statistic, 0.3, 1e-15);
  EXPECT_TRUE(r.exact);
  EXPECT_NEAR(r.p_value, 1 - ks_cdf_exact(0.3, 3), 1e-15);
  EXPECT_GT(r.p_value, 0.5);
}

TEST(KsTest, UniformAcceptedSkewedRejected) {
  std::vector<double> u(2000), skew(2000), normal(2000);
  for (std::uint64_t i = 0; i < u.size(); ++i) {
    u[i] = testing::uniform(11, i, 0);
    skew[i] = std::pow(u[i], 1.2);  // a mild distortion of the uniform
    normal[i] = testing::normal(12, i);
  }
  const KsResult a = ks_test_uniform(u);
  EXPECT_GT(a.p_value, 1e-3) << a.statistic;
  const KsResult b = ks_test_uniform(skew);
  EXPECT_LT(b.p_value, 1e-3) << b.statistic;
  const KsResult c = ks_test(normal, [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); });
  EXPECT_GT(c.p_value, 1e-3) << c.statistic;
  std::cout << "KS uniform p=" << a.p_value << " (exact " << a.exact << "), x^1.2 p=" << b.p_value
            << ", normal p=" << c.p_value << "\n";
}

// The exact distribution is itself calibrated: p-values of many small-n KS tests on uniform data
// are uniform (a KS test of KS p-values).
TEST(KsTest, PValuesOfUniformDataAreUniform) {
  std::vector<double> p(400);
  for (std::uint64_t s = 0; s < p.size(); ++s) {
    std::vector<double> x(25);
    for (std::uint64_t i = 0; i < x.size(); ++i) x[i] = testing::uniform(1000 + s, i, 0);
    p[s] = ks_test_uniform(x).p_value;
  }
  const KsResult r = ks_test_uniform(p);
  EXPECT_GT(r.p_value, 1e-3) << r.statistic;
  std::cout << "KS of 400 KS p-values (n = 25): D=" << r.statistic << " p=" << r.p_value << "\n";
}

}  // namespace
}  // namespace glintlab::verify
