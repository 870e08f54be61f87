// The Kemppinen glint claims (verify/claims/kemppinen_glints.cpp) at reduced sizes: each correct
// input passes and its negative control is rejected; the full quick-budget runs are in
// registry_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "verify/check.h"
#include "verify/claims/kemppinen_probes.h"

namespace glintlab::verify {
namespace {

void expect_probe(const ControlProbe& p, const std::string& what) {
  EXPECT_TRUE(p.correct_passes()) << what << ": correct " << p.correct << " vs " << p.threshold;
  EXPECT_TRUE(p.control_rejected()) << what << ": control " << p.control << " vs " << p.threshold;
}

TEST(KemppinenClaims, Convergence) { expect_probe(probe_kemppinen_convergence(), "convergence"); }
TEST(KemppinenClaims, Compensation) {
  expect_probe(probe_kemppinen_compensation(), "compensation");
}
// The decision on a reduced grid holds for Eq. 11 and fails on a broken input (C dropped).
TEST(KemppinenClaims, CompensationDecisionFailsWithoutC) {
  const auto [eq11, without_c] = probe_kemppinen_compensation_verdicts();
  EXPECT_EQ(eq11, Verdict::kHolds);
  EXPECT_EQ(without_c, Verdict::kFails);
}
TEST(KemppinenClaims, CompensationK16) {
  expect_probe(probe_kemppinen_compensation_k16(), "compensation k = 16 vs k = 4");
}
TEST(KemppinenClaims, Furnace) { expect_probe(probe_kemppinen_furnace(), "furnace"); }
TEST(KemppinenClaims, Roulette) { expect_probe(probe_kemppinen_roulette(), "roulette"); }
TEST(KemppinenClaims, RoulettePairedUnbiased) {
  const ControlProbe p = probe_kemppinen_roulette_paired();
  EXPECT_TRUE(p.correct_passes()) << "roulette vs linear: p " << p.correct << " vs " << p.threshold;
}
TEST(KemppinenClaims, Sampling) { expect_probe(probe_kemppinen_sampling(), "sampling"); }
TEST(KemppinenClaims, SamplingRendered) {
  expect_probe(probe_kemppinen_sampling_render(false), "rendered, control mixture pdf x 1.2");
}
// The finding, not a control: Algorithm 2's printed pdf biases the rendered estimate (~3x low).
TEST(KemppinenClaims, SamplingRenderedPrintedPdfBiased) {
  expect_probe(probe_kemppinen_sampling_render(true), "rendered, printed pdf");
}

// Holds, and its control (a LOD 2 % of λ too fine, the block widened to cover the footprint) fails.
TEST(KemppinenClaims, ConstantTimeAndControl) {
  for (const Check& c : registered_checks())
    if (c.id == "kemppinen.constant-time") {
      const CheckResult r = c.run(Budget::kQuick);
      EXPECT_EQ(r.verdict, Verdict::kHolds) << r.detail;
      EXPECT_TRUE(r.control_rejected) << r.control;
      EXPECT_EQ(r.control_verdict, Verdict::kFails) << r.control;
      return;
    }
  FAIL() << "kemppinen.constant-time not registered";
}

}  // namespace
}  // namespace glintlab::verify
