// podee.* claims (verify/claims/podee.cpp) at reduced sizes: each statistic passes on the paper's
// method and rejects its negative control (nearest-corner selection; the selected vector without
// result weighting), and the registered checks are present with their recorded verdicts.
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

TEST(PodeeClaims, BrightestVectorRejectsTheNearestCornerRule) {
  expect_probe(probe_podee_brightest_vector(100), "podee.brightest-vector");
}

// At the near distance the method beats both baselines (the regime where podee.rmse holds); the
// unweighted control does not.
TEST(PodeeClaims, RmseRejectsTheUnweightedControl) {
  expect_probe(probe_podee_rmse(2, 32), "podee.rmse");
}

TEST(PodeeClaims, StabilityRejectsTheUnweightedControl) {
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
