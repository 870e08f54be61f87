// Pearson statistic, pooling and power helpers against known answers.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <vector>

#include "verify/stats/chi_square.h"

namespace glintlab::verify {
namespace {

TEST(Pearson, TextbookPValues) {
  // Four cells, E = 25 each, O = 30, 20, 25, 25: X² = 2, dof 3.
  const std::vector<std::int64_t> o{30, 20, 25, 25};
  const std::vector<double> e{25, 25, 25, 25};
  const PearsonResult r = pearson_chi_square(o, e);
  EXPECT_NEAR(r.statistic, 2.0, 1e-15);
  EXPECT_EQ(r.dof, 3);
  // P(χ²₃ > 2) = erfc(1) + √(4/π)·e^{−1} = 0.5724067.
  EXPECT_NEAR(r.p_value, std::erfc(1.0) + std::sqrt(4 / 3.141592653589793) * std::exp(-1.0), 1e-13);
  EXPECT_NEAR(r.p_value, 0.5724067, 1e-7);
  // Critical values: χ²₁ at 5 % is 3.841458820694124, χ²₁₀ at 5 % is 18.307038053275146.
  const boost::math::chi_squared_distribution<double> one(1), ten(10);
  EXPECT_NEAR(boost::math::cdf(boost::math::complement(one, 3.841458820694124)), 0.05, 1e-12);
  EXPECT_NEAR(boost::math::cdf(boost::math::complement(ten, 18.307038053275146)), 0.05, 1e-12);
  // Unnormalised expectations with constraints = 0 (Poisson cells): dof = cells.
  EXPECT_EQ(pearson_chi_square(o, e, 5, 0).dof, 4);
}

TEST(Pooling, RuleAndZeroBins) {
  // E: 1, 0, 2, 3, 7, 0.5, 0.5: groups {1, 2, 3} (E = 6), {7}, then {0.5, 0.5} joins {7}.
  const std::vector<double> e{1, 0, 2, 3, 7, 0.5, 0.5};
  const Pooling p = pool_bins(e, 5);
  EXPECT_EQ(p.cells, 2u);
  EXPECT_EQ(p.group[0], 0u);
  EXPECT_EQ(p.group[1], kZeroExpectationBin);
  EXPECT_EQ(p.group[2], 0u);
  EXPECT_EQ(p.group[3], 0u);
  EXPECT_EQ(p.group[4], 1u);
  EXPECT_EQ(p.group[5], 1u);
  EXPECT_EQ(p.group[6], 1u);
  // Everything short: one cell.
  const std::vector<double> tiny{1, 1};
  EXPECT_EQ(pool_bins(tiny, 5).cells, 1u);
  // dof ≤ 0: no test.
  const std::vector<std::int64_t> o{2, 0};
  EXPECT_TRUE(std::isnan(pearson_chi_square(o, tiny).p_value));
}

// For dof = 1, χ'² = (Z + √λ)²: power at level 5 % is Φ(√λ − 1.96) + Φ(−√λ − 1.96), so 90 %
// power needs √λ ≈ 1.95996 + 1.28155: λ ≈ 10.5074 (the textbook 10.51).
TEST(Power, MinDetectableNoncentrality) {
  const double l1 = min_detectable_noncentrality(1, 0.05, 0.9);
  EXPECT_NEAR(l1, 10.5074, 1e-3);
  const boost::math::normal_distribution<double> z;
  const double s = std::sqrt(l1), c = boost::math::quantile(z, 0.975);
  EXPECT_NEAR(boost::math::cdf(z, s - c) + boost::math::cdf(z, -s - c), 0.9, 1e-8);
  // At any dof the power at λ_min is the asked one.
  for (double dof : {3.0, 99.0, 4095.0}) {
    for (double level : {1e-3, 5e-4}) {
      const double l = min_detectable_noncentrality(dof, level, 0.9);
      const double crit = boost::math::quantile(
          boost::math::complement(boost::math::chi_squared_distribution<double>(dof), level));
      const double power = boost::math::cdf(boost::math::complement(
          boost::math::non_central_chi_squared_distribution<double>(dof, l), crit));
      EXPECT_NEAR(power, 0.9, 1e-6) << dof;
    }
  }
  // Relative error model λ = N f δ²: a pdf scaled by 1 + δ over everything (f = 1).
  const double d = min_detectable_relative_error(1e6, 99, 5e-4, 1.0);
  EXPECT_NEAR(1e6 * d * d, min_detectable_noncentrality(99, 5e-4), 1e-6);
  std::cout << "λ_min(99 dof, 5e-4, 90%) = " << min_detectable_noncentrality(99, 5e-4)
            << " → δ = " << d << " at N = 1e6; λ_min(4095 dof) = "
            << min_detectable_noncentrality(4095, 5e-4) << "\n";
}

}  // namespace
}  // namespace glintlab::verify
