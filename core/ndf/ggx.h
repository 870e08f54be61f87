// Anisotropic GGX (Trowbridge–Reitz) NDF: D, Smith Λ, projected area, and the stretch that maps it
// to the uniform-hemisphere configuration. Walter et al. 2007 Eq. 33–34 (anisotropic form of Heitz
// 2014 "Understanding the masking-shadowing function", Eq. 85–86).
#pragma once

#include "core/math/vec.h"

namespace glintlab {

// Roughness along the tangent (x) and bitangent (y) axes of the local frame, z = normal.
template <class T>
struct GGX {
  T alpha_x, alpha_y;

  // D(m) = 1 / (π αx αy (mx²/αx² + my²/αy² + mz²)²) for mz > 0 (Heitz 2014 Eq. 85, written in
  // the stretched form so it stays accurate near the horizon and for tiny α).
  GLINTLAB_INLINE T D(Vec3<T> m) const {
    const T e = sqr(m.x / alpha_x) + sqr(m.y / alpha_y) + sqr(m.z);
    const T d = T(kInvPi<T>) / (alpha_x * alpha_y * e * e);
    return select(m.z > T(0), d, T(0));
  }

  // σ(ω)² = αx² ωx² + αy² ωy²: squared projected roughness times sin²θ.
  GLINTLAB_INLINE T sigma2(Vec3<T> w) const { return sqr(alpha_x * w.x) + sqr(alpha_y * w.y); }

  // Projected area of the microsurface seen from ω, ∫ max(0, ω·m) D(m) dm (Heitz 2014 Eq. 14),
  // for every ω: (ωz + sqrt(ωz² + σ²)) / 2. For ωz ≤ 0 this is the area of microfacets a
  // back-facing shading normal still sees (Eto & Tokuyoshi 2023, denominator of Eq. 7).
  // Below the horizon ωz + √(ωz² + σ²) cancels; there it is written σ²/(√(ωz² + σ²) + |ωz|).
  GLINTLAB_INLINE T projected_area(Vec3<T> w) const {
    const T s2 = sigma2(w);
    const T t = sqrt(sqr(w.z) + s2);
    return T(0.5) * select(w.z > T(0), w.z + t, safe_div(s2, t + abs(w.z)));
  }

  // Smith Λ with the convention Λ(ω)|ωz| = ∫ max(0, −ω·m) D(m) dm for every ω, so that
  // Λ(−ω) = 1 + Λ(ω) for ωz > 0 and Λ(ω) = (√(1 + α² tan²θ) − 1)/2 above the surface (Heitz 2014
  // Eq. 86). The upper branch is written without the cancellation of √(1+x) − 1.
  GLINTLAB_INLINE T lambda(Vec3<T> w) const {
    const T s2 = sigma2(w);
    const T t = sqrt(sqr(w.z) + s2);
    const T az = abs(w.z);
    const T up = s2 / (T(2) * az * (t + az));
    const T down = (t + az) / (T(2) * az);
    return select(w.z > T(0), up, down);
  }
};

}  // namespace glintlab
