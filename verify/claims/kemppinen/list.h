// Kemppinen et al.'s claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here.
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::kemppinen_claims {

struct Jacobian;          // jacobian.cpp
struct Convergence;       // convergence.cpp
struct Compensation;      // compensation.cpp
struct CompensationK16;   // compensation_k16.cpp
struct Roulette;          // roulette.cpp
struct Furnace;           // furnace.cpp
struct ConstantTime;      // constant_time.cpp
struct SamplingUnbiased;  // sampling_unbiased.cpp

using Claims = ClaimList<Jacobian, Convergence, Compensation, CompensationK16, Roulette, Furnace,
                         ConstantTime, SamplingUnbiased>;

}  // namespace glintlab::verify::kemppinen_claims
