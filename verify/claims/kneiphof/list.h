// Kneiphof & Klein's claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here.
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::kneiphof_claims {

struct TotalArea;        // total_area.cpp
struct DiscreteNdfMean;  // discrete_ndf_mean.cpp
struct Subdivision;      // subdivision.cpp
struct Convergence;      // convergence.cpp
struct CapProbability;   // cap_probability.cpp
struct LtcProbability;   // ltc_probability.cpp

using Claims =
    ClaimList<TotalArea, DiscreteNdfMean, Subdivision, Convergence, CapProbability, LtcProbability>;

}  // namespace glintlab::verify::kneiphof_claims
