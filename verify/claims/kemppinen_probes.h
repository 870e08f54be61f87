// Cheap probes of the Kemppinen glint claims (verify/claims/kemppinen_glints.cpp) for
// tests/verify/claims: each runs one check's statistic on a correct and a deliberately wrong input.
#pragma once

#include <utility>

#include "verify/check.h"
#include "verify/claims/control_probes.h"

namespace glintlab::verify {

// kemppinen.convergence, one configuration inside the regime: the far end of the bias interval of
// the area mean against D; control: the prefactor as printed.
ControlProbe probe_kemppinen_convergence();
// kemppinen.compensation, one setting where C carries most of D★^f: |bias of Eq. 11 (k = 4)
// against the brute-force Eq. 5|; control: Eq. 11 without C.
ControlProbe probe_kemppinen_compensation();
// kemppinen.compensation's decision on a reduced grid (8 settings, 60 positions): for Eq. 11 as
// given, and for a broken input, Eq. 11 without C.
std::pair<Verdict, Verdict> probe_kemppinen_compensation_verdicts();
// kemppinen.compensation-k16, one setting where k = 4 brightens: −(k = 4's error k = 16 removes
// beyond a tenth of it); control: k = 4's result with 8 % of its error removed.
ControlProbe probe_kemppinen_compensation_k16();
// kemppinen.furnace, one setting: one-sided p of a gain; control: rescaled to gain 3 %.
ControlProbe probe_kemppinen_furnace();
// kemppinen.roulette: max |E_r[R(r, w)] − w| on [2ε, 1 − 2ε]; control: the roulette weight × 1.02.
ControlProbe probe_kemppinen_roulette();
// kemppinen.roulette at reduced size: paired p of roulette vs linear, and of the roulette weight ×
// 1.02 vs linear (the control, which 1500 positions do not resolve: only `correct` is asserted).
ControlProbe probe_kemppinen_roulette_paired();
// kemppinen.sampling-unbiased, one configuration: Welch p of the marginal-pdf estimate against
// smooth-NDF sampling; control: the marginal density × 1.05.
ControlProbe probe_kemppinen_sampling();
// kemppinen.sampling-unbiased, the rendered estimate (GGX k = 4, 4 pixels, reduced counts): p of
// the exact-mixture estimate against the stratified reference; control: the mixture density ×
// 1.2, or (printed = true) the same samples with Algorithm 2's printed pdf in the mixture.
ControlProbe probe_kemppinen_sampling_render(bool printed);

}  // namespace glintlab::verify
