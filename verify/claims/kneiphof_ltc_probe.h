// Cheap probe of kneiphof.ltc-probability (verify/claims/kneiphof_ltc.cpp): the LTC p's error on
// one cell of the sweep and a control's, so a test asserts that the control is rejected.
#pragma once

#include "verify/check.h"
#include "verify/claims/control_probes.h"

namespace glintlab::verify {

// √α = 0.5, θv = 40°, a 0.5 square on the mirror direction: rel. error of the BRDF LTC lobe × D_PR
// against Monte Carlo; control: the lobe looked up at 2α.
ControlProbe probe_kneiphof_ltc_probability();

// The check's decide steps on four regime cells. Probability level (the stronger reading, 10 %):
// an independent Monte Carlo D_Ωh × 1.03 (must hold), the reference × 1.2 (a deliberately broken
// p, must fail) and the lobe looked up at 2α. Rendered (the claim's, 2 %): the pixel with the
// near-truth p over every density (fails: at one reflecting facet per pixel the pixel's
// fluctuation moves by more than 2 % for a 3 % error, so the check reports inconclusive there)
// and over λ ≥ 100 alone (must hold), the LTC pixel rendered 4 % brighter (must fail), the pixel
// with the reference p × 1.2 (broken, must fail) and the reference's own pixel 4 % brighter (must
// fail).
struct LtcDecisionProbe {
  Verdict near_truth, broken, wrong_alpha;
  Verdict rendered_near_truth, rendered_near_truth_dense, rendered_brighter, rendered_broken,
      rendered_reference_brighter;
};
LtcDecisionProbe probe_kneiphof_ltc_decision();

}  // namespace glintlab::verify
