// Podee et al.'s claims in registry order, one file each in this folder (verify/claim.h says what
// a claim type is). A new claim: its file, and its line here
// (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::podee_claims {

using Claims = ClaimList<
    struct BrightestVector,  // brightest_vector.cpp
    struct Rmse,             // rmse.cpp
    struct FarFailure,       // far_failure.cpp
    struct Stability>;       // stability.cpp

}  // namespace glintlab::verify::podee_claims
