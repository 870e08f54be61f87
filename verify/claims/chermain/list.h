// Chermain et al.'s claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here
// (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::chermain_claims {

using Claims = ClaimList<
    struct KernelNormalized,     // kernel_normalized.cpp
    struct DictionaryConverges,  // dictionary_converges.cpp
    struct Correlation,          // correlation.cpp
    struct GgaaError,            // ggaa_error.cpp
    struct GgaaDerivatives,      // ggaa_derivatives.cpp
    struct GgaaSk,               // ggaa_sk.cpp
    struct GgaaShimmer,          // ggaa_shimmer.cpp
    struct LeanCorrelation>;     // lean_correlation.cpp

}  // namespace glintlab::verify::chermain_claims
