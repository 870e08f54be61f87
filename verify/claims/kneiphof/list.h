// Kneiphof & Klein's claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here.
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::kneiphof_claims {

struct LtcProbability;  // ltc_probability.cpp

using Claims = ClaimList<LtcProbability>;

}  // namespace glintlab::verify::kneiphof_claims
