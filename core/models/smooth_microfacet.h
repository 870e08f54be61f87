// Shared evaluation of a smooth (non-glinty) microfacet model through core/model.h: the BRDF of
// Walter et al. 2007 Eq. 20 (F = 1, height-correlated G2 of Heitz 2014 Eq. 99) and its terms.
#pragma once

#include <array>
#include <string_view>

#include "core/model.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/sample.h"

namespace glintlab::detail {

// The intermediates every smooth model exposes, in this order.
inline constexpr std::array<std::string_view, 7> kSmoothIntermediates = {"h_x",   "h_y", "h_z", "D",
                                                                         "G1_wi", "G2",  "brdf"};

// value = f(wi, wo) max(wo_z, 0) with F = 1; `pdf` computed by the model's sampler. Forced inline
// like the kernels it calls, so no Vec3<Wide> crosses a call and no per-ISA copy has vague linkage.
template <class Ndf, class T>
GLINTLAB_INLINE ModelEval<T, 7> smooth_eval(const Ndf& ndf, const ModelQuery<T>& q, T pdf) {
  const Vec3<T> h = half_vector(q.wi, q.wo);
  const T f = microfacet_brdf(ndf, q.wi, q.wo, T(1));
  return {f * max(q.wo.z, T(0)),
          pdf,
          {h.x, h.y, h.z, ndf.D(h), smith_g1(ndf, q.wi, h),
           smith_g2_height_correlated(ndf, q.wi, q.wo, h), f}};
}

// A sampler's record as a model sample: weight = f cos / pdf (Walter et al. 2007 Eq. 20 over the
// sample density), 0 when rejected.
template <class Ndf, class T>
GLINTLAB_INLINE ModelSample<T> smooth_sample(const Ndf& ndf, Vec3<T> wi,
                                              const MicrofacetSample<T>& s) {
  return {s.wo, s.pdf, sample_weight(ndf, wi, s), s.rejected};
}

}  // namespace glintlab::detail
