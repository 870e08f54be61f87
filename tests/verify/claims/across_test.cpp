// all.stability as registered: a glintlab rule decided without a p-value. Its run at the quick
// budget (every model swept, its verdict the recorded one, its negative control, the NaN model of
// verify/stability/nan_control.h, rejected) is PluginTest.SweepFigureAndGenericClaimCoverThePlugin-
// Model (tests/cli/plugin_test.cpp), which runs it with a plug-in model beside the built-in ones:
// one sweep of every model in the suite, not two.
#include <gtest/gtest.h>

#include "verify/check.h"

namespace glintlab::verify {
namespace {

TEST(AcrossClaims, StabilityIsRegisteredAsARule) {
  const Check* c = nullptr;
  for (const Check& k : registered_checks())
    if (k.id == "all.stability") c = &k;
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(is_statistical(*c));
}

}  // namespace
}  // namespace glintlab::verify
