// Kemppinen et al.'s claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here
// (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::kemppinen_claims {

using Claims = ClaimList<
    struct Jacobian,          // jacobian.cpp
    struct Convergence,       // convergence.cpp
    struct Compensation,      // compensation.cpp
    struct CompensationK16,   // compensation_k16.cpp
    struct Roulette,          // roulette.cpp
    struct Furnace,           // furnace.cpp
    struct ConstantTime,      // constant_time.cpp
    struct SamplingUnbiased>; // sampling_unbiased.cpp

}  // namespace glintlab::verify::kemppinen_claims
