// NDF sampling for Beckmann and GGX: Walter et al. 2007, Eq. 28–29 and 35–36, pdf by Eq. 14, 24.
// Anisotropic through the slope stretch (αx, αy); the density of m is D(m) m_z (Eq. 24).
#pragma once

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/sample.h"

namespace glintlab {

// GGX, Walter Eq. 35–36: tan²θm = α² u1/(1 − u1), φ = 2π u2. Written as the stretched slope
// (αx √u1 cosφ, αy √u1 sinφ) over the height √(1 − u1): no tan, no division, so u1 → 1 and tiny α
// stay finite and exact. u in [0, 1)².
template <class T>
GLINTLAB_INLINE Vec3<T> sample_normal_walter(const GGX<T>& ggx, Vec2<T> u) {
  T sp, cp;
  sincos(T(2 * kPi<T>) * u.y, &sp, &cp);
  const T r = sqrt(u.x);
  return normalize(Vec3<T>{ggx.alpha_x * r * cp, ggx.alpha_y * r * sp, sqrt(T(1) - u.x)});
}

// Beckmann, Walter Eq. 28–29: tan²θm = −α² log(1 − u1), φ = 2π u2, as the stretched slope
// (αx ρ cosφ, αy ρ sinφ, 1) with ρ = √(−log1p(−u1)) (log1p keeps small u1 exact). u in [0, 1)².
template <class T>
GLINTLAB_INLINE Vec3<T> sample_normal_walter(const Beckmann<T>& beckmann, Vec2<T> u) {
  T sp, cp;
  sincos(T(2 * kPi<T>) * u.y, &sp, &cp);
  const T rho = sqrt(-log1p(-u.x));
  return normalize(Vec3<T>{beckmann.alpha_x * rho * cp, beckmann.alpha_y * rho * sp, T(1)});
}

// Density of wo = reflect(wi, m), m ~ D(m) m_z: D(h⁺) h⁺_z / (4 |wo·h⁺|) (Walter Eq. 14 and 24 with
// pm = D m_z). h⁺ is the half vector flipped into the upper hemisphere: a normal with wi·m < 0
// reflects to a wo whose half vector is −m, so this is the density of every produced wo, rejected
// ones included, and integrates to 1 over the sphere. |wo·h⁺| is evaluated as |wi + wo|/2 (equal
// for unit vectors): the dot product would cancel near wo = −wi, where this density has its
// integrable 1/|wi + wo| singularity.
template <class Ndf, class T>
GLINTLAB_INLINE T pdf_walter(const Ndf& ndf, Vec3<T> wi, Vec3<T> wo) {
  const Vec3<T> sum = wi + wo;
  const T l2 = dot(sum, sum);
  const Mask<T> ok = l2 > T(0);
  const T len = sqrt(select(ok, l2, T(1)));
  const Vec3<T> h = (T(1) / len) * sum;
  const Vec3<T> hp = select(h.z < T(0), -h, h);
  return select(ok, ndf.D(hp) * hp.z / (T(2) * len), T(0));
}

// Reflection through an NDF-sampled normal; rejected where wo is below the surface, m faces away,
// or the pdf underflows to 0.
template <class Ndf, class T>
GLINTLAB_INLINE MicrofacetSample<T> sample_walter(const Ndf& ndf, Vec3<T> wi, Vec2<T> u) {
  const Vec3<T> m = sample_normal_walter(ndf, u);
  const Vec3<T> wo = reflect(wi, m);
  const T pdf = pdf_walter(ndf, wi, wo);
  return {wo, m, pdf, detail::reflection_rejected(wi, m, wo, pdf)};
}

}  // namespace glintlab
