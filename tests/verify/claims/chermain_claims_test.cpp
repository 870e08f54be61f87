// chermain.*: on small inputs each check's statistic passes for the correct input and rejects its
// negative control (the full quick-budget runs are in registry_test.cpp).
#include <gtest/gtest.h>

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

TEST(ChermainClaims, GgaaControlRejected) {
  const GgaaMeasurement m = measure_ggaa({32, 22, 16, 2, 2}, 1);
  EXPECT_TRUE(judge_ggaa(m, m.reference).ggaa_lowers);
  EXPECT_FALSE(judge_ggaa(m, m.none).ggaa_lowers);  // the control
}

TEST(ChermainClaims, LeanControlRejected) {
  EXPECT_TRUE(lean_holds(measure_lean({40, 28, 16, 1, 2, 2}, 1)));
  EXPECT_FALSE(lean_holds(measure_lean({40, 28, 16, 1, 0, 2}, 1)));  // axis-aligned grooves
}

}  // namespace
}  // namespace glintlab::verify
