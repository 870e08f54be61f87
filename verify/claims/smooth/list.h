// The smooth microfacet baselines' claims (Walter et al. 2007; Heitz 2014, 2018; Heitz & d'Eon
// 2014; Dupuy & Benyoub 2023; Eto & Tokuyoshi 2023) in registry order, one file each in this folder
// (verify/claim.h says what a claim type is). A new claim: its file, and its line here
// (`struct Type,  // file.cpp`: the line declares the type where the list names it).
#pragma once

#include "verify/claim.h"

namespace glintlab::verify::smooth_claims {

using Claims = ClaimList<
    struct ProjectedArea,       // projected_area.cpp
    struct VndfNormalized,      // vndf_normalized.cpp
    struct SamplerMatchesPdf,   // sampler_matches_pdf.cpp
    struct EvalPdfConsistency>; // eval_pdf_consistency.cpp

}  // namespace glintlab::verify::smooth_claims
