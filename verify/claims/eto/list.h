// Eto & Tokuyoshi's claims in registry order, one file each in this folder (verify/claim.h says
// what a claim type is). A new claim: its file, and its line here.
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::eto_claims {

struct PdfMatches;  // pdf_matches.cpp

using Claims = ClaimList<PdfMatches>;

}  // namespace glintlab::verify::eto_claims
