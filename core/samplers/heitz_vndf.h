// GGX VNDF sampler by stretch + projected-disk warp: Heitz 2018, JCGT 7(4), Sec. 3–4, Eq. 1.
// "Sampling the GGX Distribution of Visible Normals": the five steps of Sec. 3, the density Eq. 1.
#pragma once

#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/sample.h"

namespace glintlab {

// Visible normal for wi_z > 0, u in [0, 1)². Heitz 2018 Sec. 3.
template <class T>
GLINTLAB_INLINE Vec3<T> sample_normal_heitz_vndf(const GGX<T>& ggx, Vec3<T> wi, Vec2<T> u) {
  // Step 1: stretch wi to the α = 1 configuration, where visible normals of the hemisphere are
  // the projection of a uniform disk.
  const Vec3<T> v = normalize(Vec3<T>{ggx.alpha_x * wi.x, ggx.alpha_y * wi.y, wi.z});
  // Step 2: basis (t1, t2, v); t1 ⊥ v in the tangent plane. At v = +z any t1 works: select
  // (1, 0, 0) rather than branch, and never divide by zero.
  const T l2 = sqr(v.x) + sqr(v.y);
  const Mask<T> tilted = l2 > T(0);
  const T inv = rsqrt(select(tilted, l2, T(1)));
  const Vec3<T> t1{select(tilted, -v.y * inv, T(1)), select(tilted, v.x * inv, T(0)), T(0)};
  const Vec3<T> t2 = cross(v, t1);
  // Step 3: uniform point on the unit disk; the half-disk hidden by the tilt is compressed
  // (p2 blended towards the disk edge with weight (1 + v_z)/2).
  T sp, cp;
  sincos(T(2 * kPi<T>) * u.y, &sp, &cp);
  const T r = sqrt(u.x);
  const T p1 = r * cp;
  const T blend = T(0.5) * (T(1) + v.z);
  const T p2 = fma(blend, r * sp, (T(1) - blend) * safe_sqrt(T(1) - p1 * p1));
  // Step 4: lift the disk point onto the hemisphere around v.
  const T pz = safe_sqrt(T(1) - p1 * p1 - p2 * p2);
  const Vec3<T> nh = p1 * t1 + p2 * t2 + pz * v;
  // Step 5: unstretch (normals transform with the inverse-transpose, i.e. multiply the slope part).
  return detail::normalize_or(Vec3<T>{ggx.alpha_x * nh.x, ggx.alpha_y * nh.y, max(nh.z, T(0))},
                              Vec3<T>{T(0), T(0), T(1)});
}

// Density of the reflected direction: D_wi(h)/(4 |wo·h|) (Heitz 2018 Eq. 1 with Walter Eq. 14).
template <class T>
GLINTLAB_INLINE T pdf_heitz_vndf(const GGX<T>& ggx, Vec3<T> wi, Vec3<T> wo) {
  return pdf_vndf_reflection(ggx, wi, wo);
}

// Reflection through a visible normal. Defined for wi_z > 0; for wi_z <= 0 every sample is
// rejected.
template <class T>
GLINTLAB_INLINE MicrofacetSample<T> sample_heitz_vndf(const GGX<T>& ggx, Vec3<T> wi, Vec2<T> u) {
  const Vec3<T> m = sample_normal_heitz_vndf(ggx, wi, u);
  const Vec3<T> wo = reflect(wi, m);
  const T pdf = pdf_heitz_vndf(ggx, wi, wo);
  return {wo, m, pdf, detail::reflection_rejected(wi, m, wo, pdf) || (wi.z <= T(0))};
}

}  // namespace glintlab
