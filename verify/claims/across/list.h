// The across-method claims (glintlab's own rule all.stability, one claim per kind of breakage) in
// registry order, one file each in this folder (verify/claim.h says what a claim type is). They
// judge one sweep of every registered model, measured once per process (common.h).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::across_claims {

struct Stability;    // stability.cpp
struct EnergyGain;   // energy_gain.cpp
struct Probability;  // probability.cpp
struct Variance;     // variance.cpp

using Claims = ClaimList<Stability, EnergyGain, Probability, Variance>;

}  // namespace glintlab::verify::across_claims
