// chermain.*: on small inputs each check's statistic passes for the correct input and rejects its
// negative control (the full quick-budget runs are in registry_test.cpp).
#include <gtest/gtest.h>

#include <vector>

#include "verify/claims/chermain_probes.h"

namespace glintlab::verify {
namespace {

void expect_probe(const ControlProbe& p, const char* what) {
  EXPECT_TRUE(p.correct_passes()) << what << ": correct " << p.correct << " vs " << p.threshold;
  EXPECT_TRUE(p.control_rejected()) << what << ": control " << p.control << " vs " << p.threshold;
}

TEST(ChermainClaims, KernelNormalized) {
  expect_probe(probe_chermain_kernel_normalized(), "chermain.kernel-normalized");
}
TEST(ChermainClaims, DictionaryConverges) {
  expect_probe(probe_chermain_dictionary_converges(), "chermain.dictionary-converges");
}
TEST(ChermainClaims, Correlation) {
  expect_probe(probe_chermain_correlation(), "chermain.correlation");
}

// chermain.ggaa-error's measure and decide on four small replicates: GGAA lowers the RMSE beyond
// the replicate noise; with a near-truth image (an independent reference × 1.03) in place of the
// no-GGAA image the same decision fails; a difference that is pure noise (two halves of the same
// replicates, sign-flipped) is a tie, not a win.
TEST(ChermainClaims, GgaaDecisionFailsAgainstNearTruth) {
  std::vector<GgaaReplicate> reps;
  for (int k = 0; k < 4; ++k)
    reps.push_back(measure_ggaa_replicate({32, 22, 16, 2, 4, 2}, "chermain.ggaa-test", k));
  std::vector<double> genuine, control, noise;
  for (std::size_t k = 0; k < reps.size(); ++k) {
    genuine.push_back(reps[k].none - reps[k].proj05);
    control.push_back(reps[k].near_truth - reps[k].proj05);
    noise.push_back((k % 2 ? 1 : -1) * 0.01 * double(k + 1));
  }
  EXPECT_EQ(decide_ggaa({genuine}), Verdict::kHolds);
  EXPECT_EQ(decide_ggaa({control}), Verdict::kFails);
  EXPECT_EQ(decide_ggaa({noise}), Verdict::kInconclusive);
  EXPECT_EQ(decide_ggaa({genuine, control}), Verdict::kFails);  // one part reversed: fails
}

// chermain.ggaa-derivatives / ggaa-sk's measure and decide on four small replicates of the
// normal-mapped tubes: a claimed winner that is deliberately worse (GGAA s_K 0.5 claimed below an
// independent reference × 1.03) fails; the near-truth image as the claimed winner holds; a
// reversal smaller than the tolerance is a tie, one beyond it fails.
TEST(ChermainClaims, OrderingDecisionFailsOnABrokenInput) {
  std::vector<BumpyGgaaReplicate> reps;
  for (int k = 0; k < 4; ++k)
    reps.push_back(measure_bumpy_ggaa_replicate({32, 22, 256, 4, 2}, "chermain.ggaa-fig9-test", k));
  std::vector<double> broken, corrected;
  for (const BumpyGgaaReplicate& r : reps) {
    EXPECT_GT(r.reference_error, 0);
    EXPECT_GT(r.width_ratio, 0);
    broken.push_back(r.near_truth - r.proj05);     // claim: proj05 below the near-truth image
    corrected.push_back(r.proj05 - r.near_truth);  // claim: the near-truth image below proj05
  }
  EXPECT_EQ(decide_ordering({broken}, kPairTolerance), Verdict::kFails);
  EXPECT_EQ(decide_ordering({corrected}, kPairTolerance), Verdict::kHolds);
  EXPECT_EQ(decide_ordering({corrected, broken}, kPairTolerance), Verdict::kFails);
  const std::vector<double> small_reversal = {-0.051, -0.049, -0.050, -0.052, -0.048};
  const std::vector<double> large_reversal = {-0.51, -0.49, -0.50, -0.52, -0.48};
  EXPECT_EQ(decide_ordering({small_reversal}, kPairTolerance), Verdict::kInconclusive);
  EXPECT_EQ(decide_ordering({large_reversal}, kPairTolerance), Verdict::kFails);
}

// chermain.lean-correlation's measure and decide on four small replicates: LEAN with rho beats
// both other methods; with a near-truth image (an independent reference × 1.03) in place of both,
// its margin is negative. At this size the replicate noise leaves the control's decision itself
// open; the registry's quick-budget test asserts that it fails.
TEST(ChermainClaims, LeanMarginNegativeAgainstNearTruth) {
  const LeanDecisionProbe p = probe_chermain_lean({48, 32, 64, 1, 2, 2}, 4);
  EXPECT_EQ(p.genuine, Verdict::kHolds) << to_string(p.genuine);
  EXPECT_LT(p.control_margin, 0) << p.control;
  EXPECT_NE(p.near_truth, Verdict::kHolds) << p.control;
}

}  // namespace
}  // namespace glintlab::verify
