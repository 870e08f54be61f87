// Anisotropic Beckmann NDF: D, Smith Λ and projected area. Walter et al. 2007 Eq. 25–27;
// Heitz 2014 "Understanding the masking-shadowing function", Eq. 80–83.
#pragma once

#include "core/math/vec.h"

namespace glintlab {

template <class T>
struct Beckmann {
  T alpha_x, alpha_y;

  // D(m) = exp(−(mx²/αx² + my²/αy²)/mz²) / (π αx αy mz⁴) for mz > 0 (Heitz 2014 Eq. 80).
  GLINTLAB_INLINE T D(Vec3<T> m) const {
    const T z2 = sqr(m.z);
    const T safe_z2 = select(m.z > T(0), z2, T(1));
    const T slope2 = (sqr(m.x / alpha_x) + sqr(m.y / alpha_y)) / safe_z2;
    // e^{−s} applied as two halves, one after the division, so that D keeps its precision where
    // e^{−s} alone would be subnormal but D is not (small α, grazing m).
    const T h = exp(T(-0.5) * slope2);
    const T d = T(kInvPi<T>) * h / (alpha_x * alpha_y * safe_z2 * safe_z2) * h;
    // h = 0 also covers mz⁴ underflowing to 0 at grazing m (0/0 in float for mz ≲ 1e-10).
    return select(m.z > T(0) && h > T(0), d, T(0));
  }

  GLINTLAB_INLINE T sigma2(Vec3<T> w) const { return sqr(alpha_x * w.x) + sqr(alpha_y * w.y); }

  // ∫ max(0, ω·m) D(m) dm for every ω (Heitz 2014 Eq. 14 with Eq. 83):
  // (ωz + |ωz| erf(a))/2 + σ exp(−a²)/(2√π), a = |ωz|/σ. Finite at ωz = 0 and at σ = 0.
  GLINTLAB_INLINE T projected_area(Vec3<T> w) const {
    const T sigma = sqrt(sigma2(w));
    const T az = abs(w.z);
    const Mask<T> normal = sigma == T(0);
    const T a = az / select(normal, T(1), sigma);
    const T tail = select(normal, T(0), sigma * exp_neg_sqr(a));
    const T erfc_a = select(normal, T(0), erfc(a));
    // ½(ωz + |ωz| erf a) = max(ωz, 0) − ½|ωz| erfc a: erf a rounds to 1 while the difference it
    // carries (below the horizon, the whole result |ωz|Λ) is still far from negligible.
    return max(w.z, T(0)) + fma(T(0.28209479177387814347), tail, T(-0.5) * az * erfc_a);  // 1/(2√π)
  }

  // Smith Λ, same convention as GGX<T>::lambda: above the surface
  // Λ = (exp(−a²)/(a√π) − erfc(a))/2, a = 1/(α tanθ) = |ωz|/σ (Heitz 2014 Eq. 83, with erf − 1
  // written as −erfc so small Λ keeps its relative precision); Λ(−ω) = 1 + Λ(ω).
  GLINTLAB_INLINE T lambda(Vec3<T> w) const {
    const T sigma = sqrt(sigma2(w));
    const Mask<T> normal = sigma == T(0);
    const T a = abs(w.z) / select(normal, T(1), sigma);
    // exp(−a²) with an unrounded exponent: the difference below amplifies its error by ~2a².
    const T up = T(0.5) * (T(0.56418958354775628695) * exp_neg_sqr(a) / a - erfc(a));  // 1/√π
    const T lam = select(normal, T(0), up);
    return select(w.z > T(0), lam, T(1) + lam);
  }
};

}  // namespace glintlab
