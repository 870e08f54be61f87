// The paired-interval decision of Chermain et al.'s replicated render claims (chermain.ggaa-*,
// chermain.lean-correlation; verify/claims/chermain/common.h) on numbers made for it: what the
// claims at their probe size (claim_probes_test.cpp) do not reach, a tie within the noise and a
// reversal within the tolerance. Every claim's verdict and controls at its probe size are in
// claim_probes_test.cpp, at the quick budget in registry_test.cpp.
#include <gtest/gtest.h>

#include <vector>

#include "verify/claims/chermain/common.h"

namespace glintlab::verify::chermain_claims {
namespace {

const std::vector<double> kWin = {0.51, 0.49, 0.50, 0.52, 0.48};
const std::vector<double> kSmallReversal = {-0.051, -0.049, -0.050, -0.052, -0.048};
const std::vector<double> kLargeReversal = {-0.51, -0.49, -0.50, -0.52, -0.48};
// Pure noise: alternating signs around 0.
const std::vector<double> kNoise = {-0.01, 0.02, -0.03, 0.04};

TEST(ChermainClaims, PairedDecisionWinsTiesAndReversals) {
  EXPECT_EQ(decide_paired({kWin}), Verdict::kHolds);
  EXPECT_EQ(decide_paired({kNoise}), Verdict::kInconclusive);
  EXPECT_EQ(decide_paired({kLargeReversal}), Verdict::kFails);
  // Every part must win; one reversed part fails the claim, one tied part leaves it open.
  EXPECT_EQ(decide_paired({kWin, kLargeReversal}), Verdict::kFails);
  EXPECT_EQ(decide_paired({kWin, kNoise}), Verdict::kInconclusive);
}

TEST(ChermainClaims, ReversalWithinTheToleranceIsATie) {
  EXPECT_EQ(decide_paired({kSmallReversal}, kPairTolerance), Verdict::kInconclusive);
  EXPECT_EQ(decide_paired({kLargeReversal}, kPairTolerance), Verdict::kFails);
  EXPECT_EQ(decide_paired({kSmallReversal}), Verdict::kFails);  // without a tolerance it fails
}

TEST(ChermainClaims, PairedIntervalIsTheStudentT) {
  const PairedComparison c = compare_paired({1, 2, 3, 4}, 0.99);
  EXPECT_DOUBLE_EQ(c.mean, 2.5);
  EXPECT_NEAR(c.se, 0.6454972243679028, 1e-12);  // √(5/3 / 4)
  EXPECT_NEAR(c.t, 5.840909309733, 1e-9);        // t_{0.995, 3}
  EXPECT_NEAR(c.lo, 2.5 - c.t * c.se, 1e-12);
  EXPECT_NEAR(c.detectable, (c.t + 1.2816) * c.se, 1e-12);
}

}  // namespace
}  // namespace glintlab::verify::chermain_claims
