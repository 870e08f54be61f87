// z, t and Welch tests against published values and known distributions.
#include "verify/stats/mean_tests.h"

#include <tbb/global_control.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "verify/stats/ks.h"
#include "verify/stats/stats_test_samplers.h"

namespace glintlab::verify {
namespace {

MeanAccumulator of(const std::vector<double>& x) {
  MeanAccumulator a;
  for (double v : x) a.add(v);
  return a;
}

// Student's sleep data (Cushny & Peebles; R's `sleep`): extra hours of sleep under two drugs.
const std::vector<double> kSleep1{0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
const std::vector<double> kSleep2{1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};

// R: t.test(extra[group == 1]) → t = 1.3257, df = 9, p-value = 0.2176.
TEST(MeanTests, OneSampleTSleep) {
  const MeanTestResult r = t_test(of(kSleep1), 0.0);
  EXPECT_NEAR(r.statistic, 1.3257, 5e-5);
  EXPECT_EQ(r.dof, 9);
  EXPECT_NEAR(r.p_value, 0.2176, 5e-5);
  EXPECT_NEAR(r.estimate, 0.75, 1e-15);
}

// R: t.test(extra ~ group, data = sleep) → t = −1.8608, df = 17.776, p-value = 0.07939.
TEST(MeanTests, WelchSleep) {
  const MeanTestResult r = welch_t_test(of(kSleep1), of(kSleep2));
  EXPECT_NEAR(r.statistic, -1.8608, 5e-5);
  EXPECT_NEAR(r.dof, 17.776, 5e-4);
  EXPECT_NEAR(r.p_value, 0.07939, 5e-6);
}

// z with known σ: mean 0.75 of 10, σ = 2 → z = 0.75/(2/√10) = 1.18585, p = 2Φ(−z) = 0.23568.
TEST(MeanTests, ZTestKnownSigma) {
  const MeanTestResult r = z_test(of(kSleep1), 0.0, 2.0);
  EXPECT_NEAR(r.statistic, 0.75 / (2 / std::sqrt(10.0)), 1e-12);
  EXPECT_NEAR(r.p_value, std::erfc(r.statistic / std::sqrt(2.0)), 1e-14);
  EXPECT_NEAR(r.p_value, 0.23568, 5e-5);
  EXPECT_TRUE(std::isinf(r.dof));
}

TEST(MeanTests, AccumulatorsAgree) {
  MeanAccumulator a = of(kSleep1);
  double s = 0, s2 = 0;
  for (double v : kSleep1) s += v, s2 += v * v;
  const MeanAccumulator b = MeanAccumulator::from_sums(10, s, s2);
  EXPECT_NEAR(a.mean, b.mean, 1e-15);
  EXPECT_NEAR(a.variance(), b.variance(), 1e-13);
  // Merging halves gives the whole.
  MeanAccumulator h1, h2;
  for (std::size_t i = 0; i < 4; ++i) h1.add(kSleep1[i]);
  for (std::size_t i = 4; i < 10; ++i) h2.add(kSleep1[i]);
  h1.merge(h2);
  EXPECT_EQ(h1.n, 10u);
  EXPECT_NEAR(h1.mean, a.mean, 1e-15);
  EXPECT_NEAR(h1.m2, a.m2, 1e-13);
}

TEST(MeanTests, DegenerateCases) {
  MeanAccumulator c;
  for (int i = 0; i < 5; ++i) c.add(2.0);
  EXPECT_EQ(t_test(c, 2.0).p_value, 1.0);
  EXPECT_EQ(t_test(c, 1.0).p_value, 0.0);
  MeanAccumulator one;
  one.add(1.0);
  EXPECT_TRUE(std::isnan(t_test(one, 0.0).p_value));
}

// Means of known distributions: Uniform[0, 1] has mean ½; 1e6 samples reject 0.503 (z ≈ 10).
TEST(MeanTests, UniformMeanLargeN) {
  auto f = [](std::uint64_t i) { return testing::uniform(5, i, 0); };
  const MeanAccumulator a = accumulate_mean(f, 1'000'000);
  EXPECT_GT(z_test(a, 0.5).p_value, 1e-3);
  EXPECT_GT(z_test(a, 0.5, std::sqrt(1.0 / 12)).p_value, 1e-3);
  EXPECT_LT(z_test(a, 0.503).p_value, 1e-6);
  EXPECT_NEAR(a.variance(), 1.0 / 12, 1e-3);
  // Exponential(1) by inversion has mean 1; Welch sees a shift of 0.05 at n = 2e5 (z ≈ 11).
  auto e0 = [](std::uint64_t i) { return -std::log1p(-testing::uniform(6, i, 0)); };
  auto e1 = [](std::uint64_t i) { return 0.05 - std::log1p(-testing::uniform(7, i, 0)); };
  const MeanAccumulator x = accumulate_mean(e0, 200'000), y = accumulate_mean(e1, 200'000);
  EXPECT_GT(t_test(x, 1.0).p_value, 1e-3);
  EXPECT_LT(welch_t_test(x, y).p_value, 1e-6);
}

// Calibration: under the null the t-test's p-values are uniform (400 tests of 20 normals).
TEST(MeanTests, TTestPValuesAreUniformUnderTheNull) {
  std::vector<double> p(400);
  for (std::uint64_t s = 0; s < p.size(); ++s) {
    MeanAccumulator a;
    for (std::uint64_t i = 0; i < 20; ++i) a.add(3 + 2 * testing::normal(100 + s, i));
    p[s] = t_test(a, 3.0).p_value;
  }
  const KsResult r = ks_test_uniform(p);
  EXPECT_GT(r.p_value, 1e-3) << r.statistic;
  std::cout << "KS of 400 t-test p-values: D=" << r.statistic << " p=" << r.p_value << "\n";
}

TEST(MeanTests, ParallelAccumulationIsDeterministic) {
  auto f = [](std::uint64_t i) { return testing::normal(9, i) * 1e3 + 1e6; };
  MeanAccumulator one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = accumulate_mean(f, 300'000, 1000);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = accumulate_mean(f, 300'000, 1000);
  }
  EXPECT_EQ(std::memcmp(&one.mean, &two.mean, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&one.m2, &two.m2, sizeof(double)), 0);
}

}  // namespace
}  // namespace glintlab::verify
