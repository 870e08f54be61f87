// What kemppinen.sampling-unbiased measures beside its verdict, at its probe size (the verdict and
// controls are ClaimProbes'): Algorithm 2's printed pdf (lines 16–17, as legible) biases both the
// sampler-alone estimate and the rendered one, while the sampler with its exact densities holds.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace glintlab::verify
