// A goodness-of-fit family's directions drawn through a smooth sampler's batch kernel
// (core/simd/kernels.h, "sample.<function>/<ndf>"), and densities through a pdf kernel, shared by
// the claims that test a sampler's density (smooth.sampler-matches-pdf, eto.pdf-matches).
#pragma once

#include "verify/claims/gof_family.h"

namespace glintlab::verify {

// Directions begin .. begin + count − 1 of kernel `kernel` at ω_i = wi and roughness (ax, ay),
// sample_batch in double on simd::default_isa() (GLINTLAB_ISA or the widest ISA of this CPU),
// from gof_family.h's uniform_pair: the uniforms of the scalar sampler's directions, so the same
// bits on the scalar ISA and within the batches' equivalence budgets on the others. With
// `upper_only` a direction not above the surface is (0, 0, 0), a rejected sample.
SeededDirectionBatch kernel_direction_batch(int kernel, Vec3<double> wi, double ax, double ay,
                                            bool upper_only);

// The density of a standalone pdf kernel (core/simd/kernels.h, "pdf.<function>/<ndf>", inputs
// (αx, αy, ω_i, ω_o)) at many ω_o per call, for the cubature of a chi-square plan's expected counts
// (ChiSquareOptions::direction_pdf_rows): eval_batch in double on simd::default_isa(), ω_i and α
// uniform. Within the batches' equivalence budgets of the scalar pdf (a few ULPs; bit for bit on the
// scalar ISA). With `upper_only` the density is 0 where ω_o_z ≤ 0.
DirectionPdfRows kernel_direction_pdf_rows(int kernel, Vec3<double> wi, double ax, double ay,
                                           bool upper_only);
// The same kernel with ω_i and ω_o exchanged: pdf(α, ω_o, ω_i) at many ω_o (a control's wrong pdf).
DirectionPdfRows kernel_swapped_pdf_rows(int kernel, Vec3<double> wi, double ax, double ay);

}  // namespace glintlab::verify
