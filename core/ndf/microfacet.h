// Terms every microfacet NDF shares through Smith's model: G1, the two G2 forms, the VNDF, the
// half vector and the reflection BRDF. Heitz 2014 "Understanding the masking-shadowing function"
// (Eq. 43, 98, 99), Heitz 2018 Eq. 1 (VNDF), Walter et al. 2007 Eq. 20 (BRDF).
// `Ndf` is any type with D(m), lambda(w) and projected_area(w) (GGX<T>, Beckmann<T>).
#pragma once

#include "core/math/vec.h"

namespace glintlab {

// Heaviside χ⁺(x) as a value of T.
template <class T>
GLINTLAB_FN T chi_plus(T x) {
  return select(x > T(0), T(1), T(0));
}

// Smith G1(ω, m) = χ⁺(ω·m) χ⁺(ωz) / (1 + Λ(ω)) (Heitz 2014 Eq. 43), written as ωz / A(ω) with A
// the projected area, which stays finite at grazing ω.
template <class Ndf, class T>
GLINTLAB_INLINE T smith_g1(const Ndf& ndf, Vec3<T> w, Vec3<T> m) {
  const T a = ndf.projected_area(w);
  const Mask<T> visible = (dot(w, m) > T(0)) && (w.z > T(0)) && (a > T(0));
  return select(visible, w.z / select(visible, a, T(1)), T(0));
}

// Height-correlated masking-shadowing G2 = χ⁺ χ⁺ / (1 + Λ(ωi) + Λ(ωo)) (Heitz 2014 Eq. 99).
template <class Ndf, class T>
GLINTLAB_INLINE T smith_g2_height_correlated(const Ndf& ndf, Vec3<T> wi, Vec3<T> wo, Vec3<T> m) {
  const Mask<T> ok = (dot(wi, m) > T(0)) && (dot(wo, m) > T(0)) && (wi.z > T(0)) && (wo.z > T(0));
  return select(ok, T(1) / (T(1) + ndf.lambda(wi) + ndf.lambda(wo)), T(0));
}

// Separable masking-shadowing G2 = G1(ωi, m) G1(ωo, m) (Heitz 2014 Eq. 98).
template <class Ndf, class T>
GLINTLAB_INLINE T smith_g2_separable(const Ndf& ndf, Vec3<T> wi, Vec3<T> wo, Vec3<T> m) {
  return smith_g1(ndf, wi, m) * smith_g1(ndf, wo, m);
}

// Distribution of visible normals D_ωi(m) = max(0, ωi·m) D(m) / A(ωi) (Heitz 2018 Eq. 1 with
// G1(ωi)/ωi_z = 1/A(ωi)); also defined for a back-facing shading normal ωi_z ≤ 0 (Eto &
// Tokuyoshi 2023 Eq. 7). Integrates to 1 over m for every ωi.
template <class Ndf, class T>
GLINTLAB_INLINE T vndf(const Ndf& ndf, Vec3<T> wi, Vec3<T> m) {
  const T a = ndf.projected_area(wi);
  const T c = max(dot(wi, m), T(0));
  return select(a > T(0), c * ndf.D(m) / select(a > T(0), a, T(1)), T(0));
}

// Reflection half vector normalize(ωi + ωo); the zero vector when ωo = −ωi.
template <class T>
GLINTLAB_INLINE Vec3<T> half_vector(Vec3<T> wi, Vec3<T> wo) {
  const Vec3<T> h = wi + wo;
  const T l2 = dot(h, h);
  const T inv = select(l2 > T(0), rsqrt(select(l2 > T(0), l2, T(1))), T(0));
  return inv * h;
}

// |dm/dωo| = 1 / (4 |ωo·m|) for reflection (Walter et al. 2007 Eq. 14).
template <class T>
GLINTLAB_INLINE T reflection_jacobian(Vec3<T> wo, Vec3<T> m) {
  const T c = abs(dot(wo, m));
  return select(c > T(0), T(0.25) / select(c > T(0), c, T(1)), T(0));
}

// Microfacet reflection BRDF f = F G2 D / (4 |ωi·n| |ωo·n|) (Walter et al. 2007 Eq. 20), with
// height-correlated G2 and a Fresnel factor F computed by the caller at ωi·h. Zero unless both
// directions are above the surface.
template <class Ndf, class T>
GLINTLAB_INLINE T microfacet_brdf(const Ndf& ndf, Vec3<T> wi, Vec3<T> wo, T fresnel) {
  const Vec3<T> h = half_vector(wi, wo);
  const Mask<T> ok = (wi.z > T(0)) && (wo.z > T(0));
  const T denom = T(4) * select(ok, wi.z * wo.z, T(1));
  return select(ok, fresnel * smith_g2_height_correlated(ndf, wi, wo, h) * ndf.D(h) / denom, T(0));
}

}  // namespace glintlab
