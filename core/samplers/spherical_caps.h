// GGX VNDF sampler with spherical caps: Dupuy & Benyoub 2023 (Eto & Tokuyoshi 2023 Sec. 2, Eq. 7).
// Steps (1)–(4) of Eto & Tokuyoshi Sec. 2; density Eq. 7 (= Heitz 2018 Eq. 1) × Walter et al.
// 2007 Eq. 14.
#pragma once

#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/sample.h"

namespace glintlab {

namespace detail {

// Step (1): the incident direction in the stretched (α = 1) configuration.
template <class T>
GLINTLAB_INLINE Vec3<T> ggx_stretch(const GGX<T>& ggx, Vec3<T> wi) {
  return normalize(Vec3<T>{ggx.alpha_x * wi.x, ggx.alpha_y * wi.y, wi.z});
}

// 1 + î_z = (t + i_z)/t, t = |(αx i_x, αy i_y, i_z)|: twice the height of the full cap. For
// i_z < 0 it is written σ²/(t (t − i_z)): the literal 1 + î_z cancels (measured: in float it is 0
// or twice the truth at α = 1e-3, θ = 170°, where the cap height is ~1e-8).
template <class T>
GLINTLAB_INLINE T one_plus_stretched_z(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wi_std) {
  const T len2 = ggx.sigma2(wi);
  const T t = sqrt(len2 + wi.z * wi.z);
  return select(wi.z < T(0), safe_div(len2, t * (t - wi.z)), T(1) + wi_std.z);
}

// Steps (2)–(4) for the cap ô_z in (1 − c, 1]: ô uniform on the cap, m̂ = normalize(î + ô) (the
// stretched half vector, a visible normal of the uniform hemisphere), then unstretch m̂.
// `one_plus_iz` = 1 + î_z. Listing 1's map, ô_z = (1 − u2)(1 + b) − b, is evaluated in the equal
// form ô_z = 1 − u2 c with c = 1 + b: then sinθ = √(u2 c (2 − u2 c)) and m̂_z = (1 + î_z) − u2 c
// carry no cancellation even for a cap of height ~1e-8 (back-facing wi, tiny α). The bounded
// sampler calls this same function, so its k = 1 reproduces sample_spherical_caps bit for bit.
template <class T>
GLINTLAB_INLINE Vec3<T> sample_cap_normal(const GGX<T>& ggx, Vec3<T> wi_std, T one_plus_iz, T c,
                                      Vec2<T> u) {
  T sp, cp;
  sincos(T(2 * kPi<T>) * u.x, &sp, &cp);
  const T uc = u.y * c;  // 1 − ô_z
  const T sin_theta = sqrt(max(uc * (T(2) - uc), T(0)));
  const Vec3<T> m_std{wi_std.x + sin_theta * cp, wi_std.y + sin_theta * sp, one_plus_iz - uc};
  // m_std = 0 only for ô = −î (a cap that shrinks to a point, wi = −z): any normal then gives a
  // rejected sample; +z keeps it finite.
  return normalize_or(Vec3<T>{ggx.alpha_x * m_std.x, ggx.alpha_y * m_std.y, m_std.z},
                      Vec3<T>{T(0), T(0), T(1)});
}

}  // namespace detail

// Density of the reflected direction: Eq. 7 × 1/(4|wo·h|) = D(h) / (2 (i_z + t)), t = √(i_z² + σ²)
// (the VNDF reflection density, = pdf_vndf_reflection mathematically), for every wi. For i_z < 0
// the denominator i_z + t cancels; it is evaluated as D(h) (t − i_z) / (2 σ²) there (Eto &
// Tokuyoshi Listing 2's stable form; measured: the literal form loses all digits in float at
// α = 1e-3, θ = 170°, where i_z + t ~ 1e-8).
template <class T>
GLINTLAB_INLINE T pdf_spherical_caps(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo) {
  const T ndf = ggx.D(half_vector(wi, wo));
  const T len2 = ggx.sigma2(wi);
  const T t = sqrt(len2 + wi.z * wi.z);
  const T front = ndf / (T(2) * (wi.z + t));
  const Mask<T> ok = (ndf > T(0)) && (len2 > T(0));  // wi = −z sees no microfacet
  const T back = select(ok, ndf * (t - wi.z) / (T(2) * select(ok, len2, T(1))), T(0));
  return select(wi.z >= T(0), front, back);
}

// Reflection through a visible normal sampled with the full cap ô_z in (−î_z, 1]; any wi, including
// a back-facing shading normal (wi_z <= 0). u in [0, 1)².
template <class T>
GLINTLAB_INLINE MicrofacetSample<T> sample_spherical_caps(const GGX<T>& ggx, Vec3<T> wi, Vec2<T> u) {
  const Vec3<T> wi_std = detail::ggx_stretch(ggx, wi);
  const T one_plus_iz = detail::one_plus_stretched_z(ggx, wi, wi_std);
  const Vec3<T> m = detail::sample_cap_normal(ggx, wi_std, one_plus_iz, one_plus_iz, u);
  const Vec3<T> wo = reflect(wi, m);
  const T pdf = pdf_spherical_caps(ggx, wi, wo);
  return {wo, m, pdf, detail::reflection_rejected(wi, m, wo, pdf)};
}

}  // namespace glintlab
