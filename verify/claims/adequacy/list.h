// glintlab's own adequacy claims (the binomial and Kemppinen families' levels: where a cheaper
// level is indistinguishable, and whether the engine choosers pick safely) in registry order, one
// file each in this folder (verify/claim.h says what a claim type is). A new claim: its file, and
// its line here (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::adequacy_claims {

using Claims = ClaimList<
    struct PredictionMatchesMeasurement,  // prediction_matches_measurement.cpp
    struct ChoiceIsSafe>;                 // choice_is_safe.cpp

}  // namespace glintlab::verify::adequacy_claims
