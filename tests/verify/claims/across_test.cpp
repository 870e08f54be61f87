// all.stability as registered: its verdict at the quick budget is the recorded one and its
// negative control (the NaN model of verify/stability/nan_control.h) is rejected.
#include <gtest/gtest.h>

#include "verify/check.h"

namespace glintlab::verify {
namespace {

TEST(AcrossClaims, StabilityVerdictAndControl) {
  const Check* c = nullptr;
  for (const Check& k : registered_checks())
    if (k.id == "all.stability") c = &k;
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(is_statistical(*c));
  const CheckResult r = c->run(Budget::kQuick);
  EXPECT_EQ(r.verdict, c->expected) << r.detail;
  EXPECT_TRUE(r.control_rejected) << r.control;
  ASSERT_TRUE(r.control_verdict.has_value());
  EXPECT_TRUE(control_opposes(r.verdict, *r.control_verdict)) << to_string(*r.control_verdict);
  EXPECT_EQ(r.verdict == Verdict::kHoldsInRegime, !r.regime.empty()) << r.regime;
  EXPECT_NE(r.control.find("NaN in value"), std::string::npos) << r.control;
  EXPECT_NE(r.detail.find("smooth_ggx/vndf"), std::string::npos) << r.detail;
  EXPECT_GT(r.configurations, 0);
}

}  // namespace
}  // namespace glintlab::verify
