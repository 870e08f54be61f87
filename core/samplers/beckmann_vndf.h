// Beckmann VNDF sampler: Heitz & d'Eon 2014 (visible normals), visible-slope CDF inversion.
// Smith model: stretch, sample the α = 1 visible slopes, rotate, unstretch; "Importance Sampling
// Microfacet-Based BSDFs using the Distribution of Visible Normals", CGF 33(4).
#pragma once

#include "core/ndf/beckmann.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/sample.h"

namespace glintlab {

namespace detail {

// Slope x̃ of the α = 1 Beckmann visible-slope marginal for an incidence at angle θ in the
// x̃ z-plane (c = cosθ ≥ 0, s = sinθ ≥ 0): density ∝ (c − x̃ s)⁺ exp(−x̃²) (Heitz & d'Eon 2014:
// the slope density P22 = exp(−x̃² − ỹ²)/π times the visibility factor (ωi·m)/m_z = c − x̃ s),
// solved for its u-quantile.
//
// CDF (unnormalized): F(x) = c √π/2 erfc(−x) + s/2 exp(−x²) for x ≤ cotθ, sum of two positive
// terms, so accurate in the lower tail. Upper tail: G(x) = F(hi) − F(x) written directly,
// c √π/2 (erfc(x) − erfc(hi)) − s/2 (exp(−x²) − exp(−hi²)).
//
// Both log F and log G are concave (the density is log-concave), so Newton on log F from a
// point left of the root, and on log G from a point right of it, never overshoots. The starts are
// bounds on the root: lower half, max of −√(−log u) (the θ = 90° quantile; quantiles decrease
// with θ because the density ratio between two angles is monotone) and the root of the bound
// erfc(|x|) ≤ exp(−x²); upper half, min of the bound from c − x s ≤ c (an erfc tail) and, when the
// density vanishes at hi = cotθ, of the bound G(hi − d) ≤ s d²/2. The upper-half Newton step is
// taken in log(hi − x) because G ∝ (hi − x)² near hi. A bracket with midpoint fallback guards
// rounding. Measured over θ in [0°, 90°] and u in [1e-16, 1 − 1e-16]: 5 steps already reach
// max |F(x)/F(hi) − u| = 7e-16 in double and 3e-7 in float (the float CDF's own rounding); 6 are
// taken for margin.
template <class T>
GLINTLAB_FN T beckmann_visible_slope_quantile(T c, T s, T u) {
  using S = Scalar<T>;
  // Slope range: beyond ±kMax the Gaussian carries less mass than one ulp of u.
  constexpr S kMax = sizeof(S) == 4 ? S(4.5) : S(6.5);
  // Machine epsilon and smallest normal of S, as literals (usable in every backend).
  constexpr S kEps = sizeof(S) == 4 ? S(1.1920928955078125e-7) : S(2.220446049250313080847e-16);
  constexpr S kTiny =
      sizeof(S) == 4 ? S(1.17549435082228750797e-38) : S(2.2250738585072013831e-308);
  constexpr int kSteps = 6;
  const T half_sqrt_pi = T(0.886226925452758013649);

  const Mask<T> ends_at_cot = s * T(kMax) > c;
  const T hi = select(ends_at_cot, c / select(ends_at_cot, s, T(1)), T(kMax));
  const T lo = T(-kMax);
  const T e_hi = exp(-hi * hi);
  const T erfc_hi = erfc(hi);
  const T total = c * half_sqrt_pi * (T(2) - erfc_hi) + T(0.5) * s * e_hi;  // F(hi)

  const Mask<T> upper = u > T(0.5);
  const T one_minus_u = T(1) - u;
  const T log_target = log(select(upper, one_minus_u, u) * total);

  // Lower-half start (left of the root).
  const T x_rayleigh = -safe_sqrt(-log(u));
  const T x_erfc_bound = -safe_sqrt(log((c * half_sqrt_pi + T(0.5) * s) / (u * total)));
  const T start_lower = max(max(x_rayleigh, x_erfc_bound), lo);
  // Upper-half start (right of the root).
  const Mask<T> has_c = c > T(0);
  const T q = select(
      has_c, T(2) * one_minus_u * total / (T(2) * half_sqrt_pi * select(has_c, c, T(1))), T(2));
  const T x_gauss_bound = max(erfinv(clamp(T(1) - q, T(kEps - 1), T(1 - kEps))), T(0));
  const T x_edge_bound =
      select(ends_at_cot, hi - sqrt(T(2) * one_minus_u * total / select(ends_at_cot, s, T(1))), hi);
  const T start_upper = min(min(x_gauss_bound, x_edge_bound), hi);

  T blo = select(upper, max(x_rayleigh, lo), lo);
  T bhi = hi;
  T x = clamp(select(upper, start_upper, start_lower), blo, bhi);
  for (int i = 0; i < kSteps; ++i) {
    const T e = exp(-x * x);
    const T ec = erfc(select(upper, x, -x));
    const T h = max(select(upper, c * half_sqrt_pi * (ec - erfc_hi) - T(0.5) * s * (e - e_hi),
                           c * half_sqrt_pi * ec + T(0.5) * s * e),
                    T(kTiny));
    const T g = log(h) - log_target;
    const T f = (c - x * s) * e;
    const Mask<T> too_big = (upper && (g < T(0))) || ((!upper) && (g > T(0)));
    bhi = select(too_big, x, bhi);
    blo = select(too_big, blo, x);
    const T newton_lower = x - g * h / f;
    const T d = hi - x;
    const T newton_upper = hi - d * exp(-g * h / (f * d));
    const T xn = select(upper, newton_upper, newton_lower);
    const T tol = T(8 * kEps) * (T(1) + abs(x));
    const Mask<T> inside = (xn >= blo - tol) && (xn <= bhi + tol);  // false for NaN
    x = select(inside, xn, T(0.5) * (blo + bhi));
  }
  return clamp(x, lo, hi);
}

}  // namespace detail

// Visible normal of the anisotropic Beckmann NDF for wi_z > 0, u in [0, 1)². Heitz & d'Eon 2014,
// Smith-model sampling: stretch wi by (αx, αy), sample the α = 1 visible slopes at the stretched
// θ (x̃ by the CDF inversion above, ỹ Gaussian of variance 1/2), rotate by the stretched azimuth,
// scale the slopes by (αx, αy), m = normalize(−x, −y, 1).
template <class T>
GLINTLAB_INLINE Vec3<T> sample_normal_beckmann_vndf(const Beckmann<T>& beckmann, Vec3<T> wi,
                                                Vec2<T> u) {
  const Vec3<T> v = normalize(Vec3<T>{beckmann.alpha_x * wi.x, beckmann.alpha_y * wi.y, wi.z});
  const T s = sqrt(sqr(v.x) + sqr(v.y));  // sinθ from the tangent part: exact for small θ
  const T c = max(v.z, T(0));             // wi_z <= 0 is outside the domain (sample rejected)
  const Mask<T> tilted = s > T(0);
  const T inv_s = T(1) / select(tilted, s, T(1));
  const T cos_phi = select(tilted, v.x * inv_s, T(1));
  const T sin_phi = select(tilted, v.y * inv_s, T(0));

  const T xs = detail::beckmann_visible_slope_quantile(c, s, u.x);
  // ỹ ~ exp(−ỹ²)/√π, i.e. ỹ = erfinv(2 u2 − 1). That is the same marginal at θ = 0 (c = 1, s = 0),
  // so the quantile solver gives it too, accurate in both tails: in float, 2 u2 − 1 keeps only an
  // absolute 6e-8 of 1 + y near u2 = 0 (measured: 15% error in 1 + y and 4e-3 rad in wo at
  // u2 = 1e-7 with erfinv).
  const T ys = detail::beckmann_visible_slope_quantile(T(1), T(0), u.y);

  const T x = beckmann.alpha_x * (cos_phi * xs - sin_phi * ys);
  const T y = beckmann.alpha_y * (sin_phi * xs + cos_phi * ys);
  return normalize(Vec3<T>{-x, -y, T(1)});
}

// Density of the reflected direction: D_wi(h)/(4 |wo·h|) (the VNDF of Heitz & d'Eon 2014 with
// Walter et al. 2007 Eq. 14).
template <class T>
GLINTLAB_INLINE T pdf_beckmann_vndf(const Beckmann<T>& beckmann, Vec3<T> wi, Vec3<T> wo) {
  return pdf_vndf_reflection(beckmann, wi, wo);
}

// Reflection through a visible Beckmann normal. Defined for wi_z > 0; for wi_z <= 0 every sample
// is rejected.
template <class T>
GLINTLAB_INLINE MicrofacetSample<T> sample_beckmann_vndf(const Beckmann<T>& beckmann, Vec3<T> wi,
                                                     Vec2<T> u) {
  const Vec3<T> m = sample_normal_beckmann_vndf(beckmann, wi, u);
  const Vec3<T> wo = reflect(wi, m);
  const T pdf = pdf_beckmann_vndf(beckmann, wi, wo);
  return {wo, m, pdf, detail::reflection_rejected(wi, m, wo, pdf) || (wi.z <= T(0))};
}

}  // namespace glintlab
