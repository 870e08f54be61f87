// Eto & Tokuyoshi's claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here
// (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::eto_claims {

using Claims = ClaimList<
    struct PdfMatches,           // pdf_matches.cpp
    struct Unbiased,             // unbiased.cpp
    struct BoundIsInfimum,       // bound_is_infimum.cpp
    struct FewerRejections,      // fewer_rejections.cpp
    struct VarianceRough,        // variance_rough.cpp
    struct VarianceSmooth,       // variance_smooth.cpp
    struct BackfacingStablePdf>; // backfacing_stable_pdf.cpp

}  // namespace glintlab::verify::eto_claims
