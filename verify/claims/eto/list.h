// Eto & Tokuyoshi's claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here.
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::eto_claims {

struct PdfMatches;           // pdf_matches.cpp
struct Unbiased;             // unbiased.cpp
struct BoundIsInfimum;       // bound_is_infimum.cpp
struct FewerRejections;      // fewer_rejections.cpp
struct VarianceRough;        // variance_rough.cpp
struct VarianceSmooth;       // variance_smooth.cpp
struct BackfacingStablePdf;  // backfacing_stable_pdf.cpp

using Claims = ClaimList<PdfMatches, Unbiased, BoundIsInfimum, FewerRejections, VarianceRough,
                         VarianceSmooth, BackfacingStablePdf>;

}  // namespace glintlab::verify::eto_claims
