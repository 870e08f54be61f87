// Cheap probe of kneiphof.ltc-probability (verify/claims/kneiphof_ltc.cpp): the LTC p's error on
// one cell of the sweep and a control's, so a test asserts that the control is rejected.
#pragma once

#include "verify/check.h"
#include "verify/claims/control_probes.h"

namespace glintlab::verify {

// √α = 0.5, θv = 40°, a 0.5 square on the mirror direction: rel. error of the BRDF LTC lobe × D_PR
// against Monte Carlo; control: the lobe looked up at 2α.
ControlProbe probe_kneiphof_ltc_probability();

// The check's decide step on four regime cells: an independent Monte Carlo D_Ωh × 1.03 (must hold
// within the tolerance), the reference × 1.2 (a deliberately broken p, must fail) and the lobe
// looked up at 2α.
struct LtcDecisionProbe {
  Verdict near_truth, broken, wrong_alpha;
};
LtcDecisionProbe probe_kneiphof_ltc_decision();

}  // namespace glintlab::verify
