// podee.* claims (verify/claims/podee.cpp) at reduced sizes: each statistic passes on the paper's
// method and rejects its negative control (a selection 2 % of the quad size off the closest point;
// near-truth images for podee.rmse and podee.stability), and the registered checks are present.
#include <gtest/gtest.h>

#include <string>

#include "verify/check.h"
#include "verify/claims/podee_probes.h"

namespace glintlab::verify {
namespace {

void expect_probe(const ControlProbe& p, const std::string& what) {
  EXPECT_TRUE(p.correct_passes()) << what << ": correct " << p.correct << " vs " << p.threshold;
  EXPECT_TRUE(p.control_rejected()) << what << ": control " << p.control << " vs " << p.threshold;
}

TEST(PodeeClaims, BrightestVectorRejectsASelectionTwoPercentOff) {
  expect_probe(probe_podee_brightest_vector(100), "podee.brightest-vector");
}

// podee.rmse's measure and decide at the near distance (32² crop): the method beats both
// baselines beyond the references' error; with a near-truth image (an independent reference ×
// 1.03) in place of both baselines the same decision fails, in place of the method it holds.
TEST(PodeeClaims, RmseDecisionFailsWhenTheBaselinesAreNearTruth) {
  const PodeeRmseProbe p = probe_podee_rmse(2, 32);
  EXPECT_EQ(p.genuine, Verdict::kHolds) << to_string(p.genuine);
  EXPECT_EQ(p.baselines_near_truth, Verdict::kFails) << to_string(p.baselines_near_truth);
  EXPECT_EQ(p.method_near_truth, Verdict::kHolds) << to_string(p.method_near_truth);
}

TEST(PodeeClaims, StabilityRejectsANearTruthPan) {
  expect_probe(probe_podee_stability(32, 4), "podee.stability");
}

TEST(PodeeClaims, Registered) {
  int found = 0;
  for (const Check& c : registered_checks())
    if (c.id.rfind("podee.", 0) == 0) ++found;
  EXPECT_EQ(found, 4);
}

}  // namespace
}  // namespace glintlab::verify
