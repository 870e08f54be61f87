// Podee et al.'s claims in registry order, one file each in this folder (verify/claim.h says what
// a claim type is). A new claim: its file, and its line here.
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::podee_claims {

struct BrightestVector;  // brightest_vector.cpp
struct Rmse;             // rmse.cpp
struct FarFailure;       // far_failure.cpp
struct Stability;        // stability.cpp

using Claims = ClaimList<BrightestVector, Rmse, FarFailure, Stability>;

}  // namespace glintlab::verify::podee_claims
