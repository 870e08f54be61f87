// The across-method claims (glintlab's own rule all.stability, one claim per kind of breakage) in
// registry order, one file each in this folder (verify/claim.h says what a claim type is). They
// judge one sweep of every registered model, measured once per process (common.h). A new claim:
// its file, and its line here (`struct Type,  // file.cpp`: the line declares the type).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::across_claims {

using Claims = ClaimList<
    struct Stability,    // stability.cpp
    struct EnergyGain,   // energy_gain.cpp
    struct Probability,  // probability.cpp
    struct Variance>;    // variance.cpp

}  // namespace glintlab::verify::across_claims
