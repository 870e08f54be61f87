// Kneiphof & Klein's claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here
// (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::kneiphof_claims {

using Claims = ClaimList<
    struct TotalArea,        // total_area.cpp
    struct DiscreteNdfMean,  // discrete_ndf_mean.cpp
    struct Subdivision,      // subdivision.cpp
    struct Convergence,      // convergence.cpp
    struct CapProbability,   // cap_probability.cpp
    struct LtcProbability>;  // ltc_probability.cpp

}  // namespace glintlab::verify::kneiphof_claims
