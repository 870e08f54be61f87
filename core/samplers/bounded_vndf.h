// Bounded VNDF sampler for GGX reflection: Eto & Tokuyoshi 2023, Eq. 5–8, Listings 1–2.
// Eq. 5–6: the cap bound k; Listing 1: the sampler; Eq. 8 with its Heaviside and Listing 2: the
// reflection density; Eq. 7 (i_z < 0): the full-cap density, as printed and in stable form.
#pragma once

#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/sample.h"
#include "core/samplers/spherical_caps.h"

namespace glintlab {

// Which k of Eq. 5 to use.
//  kListing1: exactly Listing 1: α = saturate(min(αx, αy)) (Eq. 6), s = 1 + |i_xy| (sgn omitted).
//  kExactIsotropic: Eq. 5 with the true α and s = 1 + sgn(1 − α)|i_xy| when αx == αy (for α > 1
//    k < 0, the cap's lower edge −k î_z is above the equator: the bound the paper calls the
//    infimum); Eq. 6's conservative α for anisotropic roughness.
enum class BoundedVndfBound { kListing1, kExactIsotropic };

// k of Eq. 5 for incidence wi (unit). Only meaningful for wi_z > 0 (the sampler uses the full cap
// otherwise); finite for every wi.
template <class T>
GLINTLAB_INLINE T bounded_vndf_k(const GGX<T>& ggx, Vec3<T> wi, BoundedVndfBound bound) {
  const T len_xy = sqrt(sqr(wi.x) + sqr(wi.y));
  const T a_conservative = saturate(min(ggx.alpha_x, ggx.alpha_y));  // Eq. 6
  if (bound == BoundedVndfBound::kListing1) {
    const T s = T(1) + len_xy;
    const T a2 = a_conservative * a_conservative;
    const T s2 = s * s;
    return (T(1) - a2) * s2 / (s2 + a2 * wi.z * wi.z);  // Eq. 5, Listing 1's arithmetic
  }
  const Mask<T> isotropic = ggx.alpha_x == ggx.alpha_y;
  const T a = select(isotropic, ggx.alpha_x, a_conservative);
  // s = 1 − |i_xy| for α > 1, written as i_z²/(1 + |i_xy|) (unit wi) to avoid the cancellation at
  // grazing incidence, where s → 0 and so does k.
  const T s = select(a > T(1), wi.z * wi.z / (T(1) + len_xy), T(1) + len_xy);
  const T a2 = a * a;
  const T s2 = s * s;
  return safe_div((T(1) - a2) * s2, s2 + a2 * wi.z * wi.z);  // 0/0 only at α > 1, i_z = 0
}

namespace detail {

// Eq. 8 × |dm/do| (i_z >= 0) or the stable form of Eq. 7 × |dm/do| (i_z < 0), without the
// Heaviside: the value of Listing 2 for a given k. `ndf` = D(h).
template <class T>
GLINTLAB_INLINE T bounded_vndf_density(const GGX<T>& ggx, Vec3<T> wi, T ndf, T k) {
  const T len2 = sqr(ggx.alpha_x * wi.x) + sqr(ggx.alpha_y * wi.y);
  const T t = sqrt(len2 + wi.z * wi.z);
  const T front = ndf / (T(2) * (k * wi.z + t));
  // (t − i_z)/len2 = 1/(i_z + t) without cancelling for i_z < 0; zero where D = 0 or len2 = 0
  // (wi = −z sees no microfacet).
  const Mask<T> ok = (ndf > T(0)) && (len2 > T(0));
  const T back = select(ok, ndf * (t - wi.z) / (T(2) * select(ok, len2, T(1))), T(0));
  return select(wi.z >= T(0), front, back);
}

}  // namespace detail

// Eq. 8 × 1/(4|i·m|) for a given k, including the Heaviside χ⁺(k î_z + ô_z), with ô the
// stretched-space reflection (m̂ ∝ (m_x/αx, m_y/αy, m_z), ô = reflect(î, m̂)); for i_z < 0 the
// full-cap density in the stable form of Listing 2. k = 1 is the spherical-cap density.
template <class T>
GLINTLAB_INLINE T pdf_bounded_vndf_with_k(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo, T k) {
  const Vec3<T> h = half_vector(wi, wo);
  const Vec3<T> wi_std = detail::ggx_stretch(ggx, wi);
  const T b = k * wi_std.z;
  const Vec3<T> m_std = detail::normalize_or(Vec3<T>{h.x / ggx.alpha_x, h.y / ggx.alpha_y, h.z},
                                             Vec3<T>{T(0), T(0), T(1)});
  const Vec3<T> o_std = reflect(wi_std, m_std);
  // For i_z <= 0 the cap is the full one, whose edge ô_z = −î_z is exactly h_z = 0, already a zero
  // of D(h): testing it again through ô (less accurate than h_z) could only flip near the edge.
  const T inside_cap = select(wi.z > T(0), chi_plus(o_std.z + b), T(1));
  return detail::bounded_vndf_density(ggx, wi, ggx.D(h), k) * inside_cap;
}

// True density of sample_bounded_vndf's wo over the whole sphere (Eq. 8 with its Heaviside).
template <class T>
GLINTLAB_INLINE T pdf_bounded_vndf(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo,
                               BoundedVndfBound bound = BoundedVndfBound::kListing1) {
  return pdf_bounded_vndf_with_k(ggx, wi, wo, bounded_vndf_k(ggx, wi, bound));
}

// Listing 2 as printed: Eq. 8 × |dm/do| with Listing 1's k and no Heaviside for i_z >= 0, the
// stable Eq. 7 form for i_z < 0. Equals pdf_bounded_vndf for wo_z > 0; over the whole sphere it
// integrates to (1 + î_z)/(1 + k î_z) > 1 — kept to check exactly that.
template <class T>
GLINTLAB_INLINE T pdf_bounded_vndf_listing2(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo) {
  const Vec3<T> h = half_vector(wi, wo);
  const T k = bounded_vndf_k(ggx, wi, BoundedVndfBound::kListing1);
  return detail::bounded_vndf_density(ggx, wi, ggx.D(h), k);
}

// Eq. 7 × 1/(4|i·m|) evaluated as printed: 2 D(m) max(i·m, 0) / (i_z + t) / (4 |o·m|). Loses
// relative precision for i_z < 0 (i_z + t cancels); kept to be compared with the stable form.
template <class T>
GLINTLAB_INLINE T pdf_vndf_backfacing_eq7(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo) {
  const Vec3<T> m = half_vector(wi, wo);
  const T t = sqrt(ggx.sigma2(wi) + wi.z * wi.z);
  const T p_m = safe_div(T(2) * ggx.D(m) * max(dot(wi, m), T(0)), wi.z + t);
  return p_m * reflection_jacobian(wo, m);
}

// The same density in Listing 2's stable form D(m) (t − i_z) / (2 len2) (exact algebra:
// 1/(i_z + t) = (t − i_z)/len2, and i·m = o·m for a half vector). Meant for i_z < 0; 0 where
// len2 = 0.
template <class T>
GLINTLAB_INLINE T pdf_vndf_backfacing_stable(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo) {
  const Vec3<T> m = half_vector(wi, wo);
  const T ndf = ggx.D(m);
  const T len2 = ggx.sigma2(wi);
  const T t = sqrt(len2 + wi.z * wi.z);
  const Mask<T> ok = (ndf > T(0)) && (len2 > T(0));
  return select(ok, ndf * (t - wi.z) / (T(2) * select(ok, len2, T(1))), T(0));
}

// Listing 1 for a given k: the spherical-cap sampler with the cap's lower edge at −k î_z when
// i_z > 0 (the full cap −î_z otherwise). rejected = wo_z <= 0 (m faces wi by construction), or a
// pdf of 0. pdf = pdf_bounded_vndf_with_k(wi, wo, k), Heaviside included, recomputed from wo: the
// round trip ô → wo → ô is ill-conditioned near wo = −wi (half vector of nearly opposite
// directions), so a produced ô at the cap edge can test outside it. Such wo lie below the horizon
// (the bound is at or below the infimum over upper-hemisphere reflections), or on it where the
// bound is tight (measured: wo_z = 2e-16 at u2 = 1 − 2^-53); they are rejected either way, and the
// reported pdf is always exactly the standalone value.
template <class T>
GLINTLAB_INLINE MicrofacetSample<T> sample_bounded_vndf_with_k(const GGX<T>& ggx, Vec3<T> wi, Vec2<T> u,
                                                           T k) {
  const Vec3<T> wi_std = detail::ggx_stretch(ggx, wi);
  const T one_plus_iz = detail::one_plus_stretched_z(ggx, wi, wi_std);
  const T c = select(wi.z > T(0), T(1) + k * wi_std.z, one_plus_iz);  // 1 + b of Listing 1
  const Vec3<T> m = detail::sample_cap_normal(ggx, wi_std, one_plus_iz, c, u);
  const Vec3<T> wo = reflect(wi, m);
  const T pdf = pdf_bounded_vndf_with_k(ggx, wi, wo, k);
  return {wo, m, pdf, detail::reflection_rejected(wi, m, wo, pdf)};
}

// Listing 1 with k from Eq. 5 for the chosen bound.
template <class T>
GLINTLAB_INLINE MicrofacetSample<T> sample_bounded_vndf(
    const GGX<T>& ggx, Vec3<T> wi, Vec2<T> u,
    BoundedVndfBound bound = BoundedVndfBound::kListing1) {
  return sample_bounded_vndf_with_k(ggx, wi, u, bounded_vndf_k(ggx, wi, bound));
}

}  // namespace glintlab
