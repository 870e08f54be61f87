// A goodness-of-fit family's directions drawn through a smooth sampler's batch kernel
// (core/simd/kernels.h, "sample.<function>/<ndf>"), shared by the claims that test a sampler's
// density (smooth.sampler-matches-pdf, eto.pdf-matches).
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

}  // namespace glintlab::verify
