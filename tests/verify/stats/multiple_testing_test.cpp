// Holm–Šidák and Šidák against hand-computed values.
#include "verify/stats/multiple_testing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace glintlab::verify {
namespace {

TEST(MultipleTesting, FamilyWiseRateIsOneInAThousand) { EXPECT_EQ(kFamilyWiseRate, 1e-3); }

TEST(MultipleTesting, SidakMinimum) {
  EXPECT_NEAR(sidak(0.01, 2), 1 - 0.99 * 0.99, 1e-15);
  EXPECT_NEAR(sidak(0.05, 1), 0.05, 1e-15);
  EXPECT_EQ(sidak(0.0, 5), 0.0);
  EXPECT_EQ(sidak(1.0, 5), 1.0);
  // Tiny p keep their relative precision: 1 − (1 − 1e-20)^3 = 3e-20.
  EXPECT_NEAR(sidak(1e-20, 3) / 3e-20, 1.0, 1e-12);
  const std::vector<double> p{0.3, 0.02, 0.5};
  EXPECT_NEAR(sidak_min(p), 1 - std::pow(0.98, 3), 1e-15);
  // The per-test level that gives α over k tests inverts sidak().
  EXPECT_NEAR(sidak(sidak_level(1e-3, 7), 7), 1e-3, 1e-15);
}

// p = (0.01, 0.04, 0.03, 0.005), m = 4. Sorted: 0.005, 0.01, 0.03, 0.04 with multipliers 4, 3, 2, 1:
//   1 − 0.995⁴ = 0.019850499375, 1 − 0.99³ = 0.029701, 1 − 0.97² = 0.0591, 1 − 0.96 = 0.04 → 0.0591
// (monotone). At α = 0.05 the step-down rejects the first two and stops at 0.03.
TEST(MultipleTesting, HolmSidakHandExample) {
  const std::vector<double> p{0.01, 0.04, 0.03, 0.005};
  const HolmSidakResult r = holm_sidak(p, 0.05);
  ASSERT_EQ(r.adjusted.size(), 4u);
  EXPECT_NEAR(r.adjusted[3], 0.019850499375, 1e-15);
  EXPECT_NEAR(r.adjusted[0], 0.029701, 1e-15);
  EXPECT_NEAR(r.adjusted[2], 0.0591, 1e-15);
  EXPECT_NEAR(r.adjusted[1], 0.0591, 1e-15);
  EXPECT_TRUE(r.reject[3]);
  EXPECT_TRUE(r.reject[0]);
  EXPECT_FALSE(r.reject[2]);
  EXPECT_FALSE(r.reject[1]);
  EXPECT_EQ(r.rejections, 2u);
  EXPECT_EQ(r.raw, p);
  // The default rate is the suite's family-wise rate: nothing here survives 1e-3.
  EXPECT_EQ(holm_sidak(p).rejections, 0u);
  EXPECT_EQ(holm_sidak(p).alpha, kFamilyWiseRate);
}

TEST(MultipleTesting, HolmSidakEdgeCases) {
  EXPECT_TRUE(holm_sidak(std::vector<double>{}).adjusted.empty());
  const std::vector<double> p{NAN, 1e-9, 0.5};
  const HolmSidakResult r = holm_sidak(p, 1e-3);
  EXPECT_EQ(r.adjusted[0], 1.0);  // NaN counts as 1
  EXPECT_FALSE(r.reject[0]);
  EXPECT_TRUE(r.reject[1]);
  EXPECT_NEAR(r.adjusted[1], 3e-9, 1e-17);  // 1 − (1 − 1e-9)³
}

}  // namespace
}  // namespace glintlab::verify
