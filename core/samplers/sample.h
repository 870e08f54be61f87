// Sample record, VNDF reflection pdf, weight shared by samplers (Heitz 2018 Eq. 1; Walter Eq. 14).
// The reflection density is Heitz 2018 Eq. 1 × Walter et al. 2007 Eq. 14; the weight is
// f·cos/pdf with f from Walter et al. 2007 Eq. 20.
#pragma once

#include "core/math/vec.h"
#include "core/ndf/microfacet.h"

namespace glintlab {

// One sampled reflection. wo = reflect(wi, m); pdf = density of wo per unit solid angle over the
// whole sphere (the value the sampler's standalone pdf function returns for this wo); rejected =
// the sample cannot carry an opaque reflection (wo below the surface, m facing away from wi, or a
// pdf that evaluates to 0 by rounding). The sampler reports rejection; it never hides it by
// returning a zero weight.
template <class T>
struct MicrofacetSample {
  Vec3<T> wo;
  Vec3<T> m;
  T pdf;
  Mask<T> rejected;
};

namespace detail {

// normalize(v), or `fallback` where v is the zero vector (a measure-zero event, e.g. ô = −î in the
// spherical-cap construction), so that no sampler ever produces NaN.
template <class T>
GLINTLAB_INLINE Vec3<T> normalize_or(Vec3<T> v, Vec3<T> fallback) {
  const T l2 = dot(v, v);
  const Mask<T> ok = l2 > T(0);
  return select(ok, rsqrt(select(ok, l2, T(1))) * v, fallback);
}

// Opaque-reflection rejection: wo under the geometric surface, or a microfacet seen from behind;
// also a sample whose density evaluates to 0 (or NaN), which no estimator can weight: this happens
// only by rounding, at the edge of a support (the bounded cap's edge where it touches the horizon,
// D(h) underflowing in a Beckmann tail), and keeps "accepted ⇒ pdf > 0" exact.
template <class T>
GLINTLAB_INLINE Mask<T> reflection_rejected(Vec3<T> wi, Vec3<T> m, Vec3<T> wo, T pdf) {
  return (wo.z <= T(0)) || (dot(wi, m) <= T(0)) || !(pdf > T(0));
}

}  // namespace detail

// Density of wo = reflect(wi, m) when m follows the VNDF D_wi (Heitz 2018 Eq. 1):
// D_wi(h) |dh/dwo| with h the half vector and |dh/dwo| = 1/(4|wo·h|) (Walter et al. 2007 Eq. 14).
// Valid over the whole sphere: every wo has exactly one half vector, and wi·h = wo·h = |wi + wo|/2
// ≥ 0 for it. That identity is used to evaluate vndf(ndf, wi, h) · reflection_jacobian(wo, h) as
// D(h) / (4 A(wi)): the literal product divides two dot products that both cancel near wo = −wi
// (measured: the float value off by 2× there), the quotient has no cancellation.
template <class Ndf, class T>
GLINTLAB_INLINE T pdf_vndf_reflection(const Ndf& ndf, Vec3<T> wi, Vec3<T> wo) {
  const Vec3<T> h = half_vector(wi, wo);
  const T a = ndf.projected_area(wi);
  return select(a > T(0), ndf.D(h) / (T(4) * select(a > T(0), a, T(1))), T(0));
}

// Monte Carlo weight f(wi, wo) wo_z / pdf with F = 1 (Walter et al. 2007 Eq. 20 over the sample
// density); 0 for a rejected sample or a zero pdf, never NaN from 0/0.
template <class Ndf, class T>
GLINTLAB_INLINE T sample_weight(const Ndf& ndf, Vec3<T> wi, const MicrofacetSample<T>& s) {
  const Mask<T> ok = (!s.rejected) && (s.pdf > T(0));
  const T f = microfacet_brdf(ndf, wi, s.wo, T(1));
  return select(ok, f * s.wo.z / select(ok, s.pdf, T(1)), T(0));
}

}  // namespace glintlab
