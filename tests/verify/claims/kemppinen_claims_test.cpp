// What kemppinen.sampling-unbiased measures beside its verdict, at its probe size (the verdict and
// controls are ClaimProbes'): Algorithm 2's printed pdf (lines 16–17, as legible) biases both the
// sampler-alone estimate and the rendered one, while the sampler with its exact densities holds;
// and kemppinen.furnace's stated power.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "verify/claim.h"
#include "verify/claims/kemppinen/list.h"

namespace glintlab::verify {
namespace {

TEST(KemppinenClaims, SamplingPrintedPdfBiasedBesideTheClaim) {
  const ClaimProbe p = probe_claim<kemppinen_claims::SamplingUnbiased>();
  const std::string& d = p.result.detail;
  EXPECT_EQ(p.result.verdict, Verdict::kHolds) << d;
  EXPECT_NE(d.find("the pdf printed in lines 16–17 (as legible) biases the estimate"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("biased — the printed pdf does not give the integral"), std::string::npos) << d;
  EXPECT_NE(d.find("with Algorithm 2's printed pdf in the mixture it is biased"), std::string::npos)
      << d;
}

// kemppinen.furnace states the smallest gain it detects at 90 % power, from its quietest setting to
// its noisiest: two finite numbers, the first the smaller (it once printed 5.8e+300 for the first).
TEST(KemppinenClaims, FurnacePowerSpansItsSettings) {
  const ClaimProbe p = probe_claim<kemppinen_claims::Furnace>();
  const std::string& power = p.result.power;
  double quietest = 0, noisiest = 0;
  ASSERT_EQ(std::sscanf(power.c_str(),
                        "a gain over the smooth NDF's energy of %lf (quietest setting) to %lf",
                        &quietest, &noisiest),
            2)
      << power;
  EXPECT_GT(quietest, 0) << power;
  EXPECT_LE(quietest, noisiest) << power;
  EXPECT_LT(noisiest, 1) << power;
}

}  // namespace
}  // namespace glintlab::verify
