// The binomial-counting claims of kneiphof.cpp: each statistic passes on the correct input and
// rejects its negative control (counts from Binomial(N, 1.05 p), facets from D cos θ, independent
// sub-light counts, Eq. 20 without its Jacobian), at reduced sizes.
#include <gtest/gtest.h>

#include <string>

#include "verify/claims/kneiphof_probes.h"

namespace glintlab::verify {
namespace {

void expect_probe(const ControlProbe& p, const std::string& what) {
  EXPECT_TRUE(p.correct_passes()) << what << ": correct input " << p.correct << " vs "
                                  << p.threshold;
  EXPECT_TRUE(p.control_rejected()) << what << ": control " << p.control << " vs " << p.threshold;
}

TEST(KneiphofClaims, DiscreteNdfMean) {
  expect_probe(probe_kneiphof_discrete_ndf_mean(), "kneiphof.discrete-ndf-mean");
}
TEST(KneiphofClaims, SubdivisionCounts) {
  expect_probe(probe_kneiphof_subdivision_counts(), "kneiphof.subdivision counts");
}
TEST(KneiphofClaims, SubdivisionInvariance) {
  expect_probe(probe_kneiphof_subdivision_invariance(), "kneiphof.subdivision invariance");
}
TEST(KneiphofClaims, Convergence) {
  expect_probe(probe_kneiphof_convergence(), "kneiphof.convergence");
}
TEST(KneiphofClaims, CapProbability) {
  expect_probe(probe_kneiphof_cap_probability(), "kneiphof.cap-probability");
}
TEST(KneiphofClaims, CapDecisionFailsOnABrokenP) {
  const CapDecisionProbe p = probe_kneiphof_cap_decision();
  EXPECT_EQ(p.eq20, Verdict::kHoldsInRegime) << to_string(p.eq20);
  EXPECT_EQ(p.no_jacobian, Verdict::kFails) << to_string(p.no_jacobian);
  // The exact p × 1.03 holds in the regime (it exceeds 1 only where the exact p is near 1).
  EXPECT_TRUE(is_holding(p.near_truth)) << to_string(p.near_truth);
}

}  // namespace
}  // namespace glintlab::verify
