// Cheap probes of the binomial-counting claims in verify/claims/kneiphof.cpp (as control_probes.h
// does for the others): each runs one check's statistic on a correct and a deliberately wrong
// input at a small size, so tests assert that the correct one passes and the control is rejected.
#pragma once

#include "verify/check.h"
#include "verify/claims/control_probes.h"

namespace glintlab::verify {

// discrete-ndf-mean at α = 0.81: multinomial p; control: facets drawn at α × 1.03.
ControlProbe probe_kneiphof_discrete_ndf_mean();
// subdivision: Σ b_k against Binomial(N_P, p); control: b from Binomial(N_P, 1.05 p).
ControlProbe probe_kneiphof_subdivision_counts();
// subdivision: shared-lobe radiance difference 1 vs 256 sub-lights; control: each sub-light's
// share of the lobe 2 % off (alternating in sign).
ControlProbe probe_kneiphof_subdivision_invariance();
// convergence at p = 0.01: |slope + ½|; control: counts from Binomial(N_P, 1.05 p).
ControlProbe probe_kneiphof_convergence();
// cap-probability at α = 0.25, γ = 0.5°: Eq. 20's error; control: the 1/(4⟨h, ω⟩) dropped.
ControlProbe probe_kneiphof_cap_probability();
// cap-probability's decide step on a 5 × 5 (√α, γ) grid: Eq. 20 (holds-in-regime), Eq. 20 without
// its Jacobian (a broken p: fails) and the exact p × 1.03 (holds in the regime).
struct CapDecisionProbe {
  Verdict eq20, no_jacobian, near_truth;
};
CapDecisionProbe probe_kneiphof_cap_decision();

}  // namespace glintlab::verify
