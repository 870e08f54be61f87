// kneiphof.ltc-probability: on one cell of the sweep the LTC p is within the tolerance of the
// Monte Carlo D_Ωh, and the negative control (the lobe looked up at 2α) is rejected.
#include <gtest/gtest.h>

#include "verify/claims/kneiphof_ltc_probe.h"

namespace glintlab::verify {
namespace {

TEST(KneiphofLtcClaims, ControlIsRejected) {
  const ControlProbe p = probe_kneiphof_ltc_probability();
  EXPECT_TRUE(p.correct_passes()) << "correct " << p.correct << " vs " << p.threshold;
  EXPECT_TRUE(p.control_rejected()) << "control " << p.control << " vs " << p.threshold;
}

}  // namespace
}  // namespace glintlab::verify
