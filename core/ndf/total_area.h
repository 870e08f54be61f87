// Total microfacet area D_H = ∫_H D dh (Kneiphof & Klein 2024 App. B, Eq. 29–31), also anisotropic.
// Eq. 29 (GGX), Eq. 30 and its fit Eq. 31 (Beckmann); the anisotropic extension is ours.
#pragma once

#include "core/math/vec.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"

namespace glintlab {

// --- Isotropic closed forms, as functions of a = α² ---------------------------------------------

// GGX: D_H = 1 + a·h(1 − a) with h(x) = atanh(√x)/√x = log((1 + √x)/α)/√x for x = 1 − α² > 0
// (Kneiphof & Klein Eq. 29), continued analytically to α ≥ 1: h(1) = 1 (D_H = 2, the uniform
// hemisphere) and h(x) = atan(√−x)/√−x = arccos(1/α)/√(α² − 1) for x < 0. Near x = 0 the series
// h = 1 + x/3 + x²/5 + x³/7 (|x| < 1e-4, next term < 1.2e-17) replaces the 0/0. x = 1 − a is exact
// for a ∈ [½, 2] (Sterbenz), and the closed forms have no cancellation, so this is a few ulp.
template <class T>
GLINTLAB_FN T total_area_ggx_iso_a2(T a) {
  const T x = T(1) - a;
  const Mask<T> below = x > T(0);
  const Mask<T> series = abs(x) < T(1e-4);
  const T sx = sqrt(select(series, T(1), abs(x)));
  // α < 1: (log1p(√x) − ½ log a)/√x, both terms positive.
  const T h_below = (log1p(sx) - T(0.5) * log(select(below, a, T(1)))) / sx;
  const T h_above = atan(sx) / sx;  // α > 1
  const T h_series = fma(fma(fma(x, T(1.0 / 7.0), T(0.2)), x, T(1.0 / 3.0)), x, T(1));
  const T h = select(series, h_series, select(below, h_below, h_above));
  return fma(a, h, T(1));
}

// Beckmann: D_H = 1 + (√π/2)·α·exp(1/α²) erfc(1/α) (Kneiphof & Klein Eq. 30), evaluated as
// 1 + (√π/2)·α·erfcx(1/α): exp(1/α²) alone overflows below α ≈ 0.106 (float) / 0.038 (double).
template <class T>
GLINTLAB_FN T total_area_beckmann_iso_a2(T a) {
  const T alpha = sqrt(a);
  return fma(T(0.88622692545275801365) * alpha, erfcx(T(1) / alpha), T(1));  // √π/2
}

// Kneiphof & Klein Eq. 29, isotropic GGX of roughness α > 0 (analytic continuation for α ≥ 1).
template <class T>
GLINTLAB_FN T total_area_ggx_eq29(T alpha) {
  return total_area_ggx_iso_a2(alpha * alpha);
}

// Kneiphof & Klein Eq. 30, isotropic Beckmann of roughness α > 0.
template <class T>
GLINTLAB_FN T total_area_beckmann_eq30(T alpha) {
  return fma(T(0.88622692545275801365) * alpha, erfcx(T(1) / alpha), T(1));
}

// Kneiphof & Klein Eq. 31, their quadratic fit of Eq. 30, as printed: 1 + 0.466 α − 0.091 α².
// Measured on α ∈ (0, 1] (tests/core/ndf/total_area_test.cpp): as printed it is up to 0.098 (9 %)
// away from Eq. 30 (near α ≈ 0.45; Eq. 30 is 1 + α²/2 + O(α⁴), the fit is linear at 0); called
// with α² in place of α it is within 4e-3 of Eq. 30, so the fit was presumably made in α².
// Kept as printed; callers choose.
template <class T>
GLINTLAB_FN T total_area_beckmann_eq31(T alpha) {
  return fma(fma(T(-0.091), alpha, T(0.466)), alpha, T(1));
}

// --- Anisotropic D_H (our extension; the paper gives the isotropic case only) --------------------
//
// For a fixed azimuth φ both anisotropic NDFs equal (α_φ²/(αx αy))·D_iso(θ; α_φ) with
// 1/α_φ² = cos²φ/αx² + sin²φ/αy², so D_H = (1/2π) ∫ (α_φ²/(αx αy)) D_H,iso(α_φ) dφ. The
// substitution tan ψ = (αx/αy) tan φ turns the weight into dψ exactly and gives
// α_φ² = αx² cos²ψ + αy² sin²ψ:
//   D_H = (2/π) ∫_0^{π/2} f(lo² cos²ψ + hi² sin²ψ) dψ,  lo = min(αx, αy), hi = max(αx, αy),
// with f the isotropic D_H as a function of α². f has a branch point at α² = 0, which sits at
// ψ ≈ ±i·lo/hi: for 1:1000 anisotropy a plain rule in ψ would need ~hi/lo nodes. The second
// substitution ψ = ε sinh τ, ε = lo/hi, moves it to Im τ ≈ ±π/2 whatever ε is, and the 32-point
// Gauss–Legendre rule on τ ∈ [0, asinh(π/(2ε))] then has a relative error below 1e-16 for
// αx, αy ∈ [1e-4, 4] and anisotropy up to 1:10⁴ (measured against adaptive Gauss–Kronrod in long
// double). Cost: 32 evaluations of f.

// Nodes x ∈ (0, 1) and weights of the 32-point Gauss–Legendre rule on [−1, 1] (the symmetric
// half, i = 0..15), computed by Newton iteration on P₃₂ in long double; tests check that the rule
// integrates polynomials up to degree 63 exactly. Local tables so device code can use them too.
inline constexpr int kGaussLegendre32Half = 16;
[[gnu::always_inline]] GLINTLAB_FN double gauss_legendre32_node(int i) {
  constexpr double k[kGaussLegendre32Half] = {
      0.997263861849481563534, 0.985611511545268335400, 0.964762255587506430761,
      0.934906075937739689159, 0.896321155766052123971, 0.849367613732569970160,
      0.794483795967942406965, 0.732182118740289680412, 0.663044266930215200960,
      0.587715757240762329012, 0.506899908932229390044, 0.421351276130635345380,
      0.331868602282127649782, 0.239287362252137074544, 0.144471961582796493484,
      0.048307665687738316236};
  return k[i];
}
[[gnu::always_inline]] GLINTLAB_FN double gauss_legendre32_weight(int i) {
  constexpr double k[kGaussLegendre32Half] = {
      0.007018610009470096558, 0.016274394730905670577, 0.025392065309262059458,
      0.034273862913021433022, 0.042835898022226680608, 0.050998059262376176206,
      0.058684093478535547158, 0.065822222776361846807, 0.072345794108848506229,
      0.078193895787070306530, 0.083311924226946755229, 0.087652093004403811172,
      0.091173878695763884754, 0.093844399080804565603, 0.095638720079274859439,
      0.096540088514727800519};
  return k[i];
}

// (2/π) ∫_0^{π/2} f(lo² cos²ψ + hi² sin²ψ) dψ by the rule above; f maps α² to the isotropic D_H.
template <class T, class F>
GLINTLAB_FN T total_area_azimuthal_average(T alpha_x, T alpha_y, F f) {
  const T lo = min(alpha_x, alpha_y);
  const T hi = max(alpha_x, alpha_y);
  const T eps = lo / hi;
  const T lo2 = lo * lo;
  const T hi2 = hi * hi;
  const T z = T(1.57079632679489661923) / eps;  // π/(2ε) ≥ π/2: asinh without cancellation
  const T tau_max = log(z + sqrt(fma(z, z, T(1))));
  const T half = T(0.5) * tau_max;
  // The same rule applied to f ≡ 1 gives (2/π)∫ε cosh τ dτ = 1 exactly; dividing by its computed
  // value cancels the rounding of the nodes, weights and of τ_max, ε in T (float: 7.9 → 5.6 ulp),
  // and makes the isotropic case exactly f(α²) up to the rounding of the quotient.
  T sum_f = T(0);
  T sum_1 = T(0);
  for (int i = 0; i < kGaussLegendre32Half; ++i) {
    for (int side = 0; side < 2; ++side) {
      const T node = T(side == 0 ? gauss_legendre32_node(i) : -gauss_legendre32_node(i));
      const T tau = fma(half, node, half);
      // sinh via expm1 so that small τ keeps its relative precision; cosh has no cancellation.
      const T sinh_tau = T(0.5) * (expm1(tau) - expm1(-tau));
      const T cosh_tau = T(0.5) * (exp(tau) + exp(-tau));
      T s, c;
      sincos(eps * sinh_tau, &s, &c);
      const T a = fma(lo2, c * c, hi2 * (s * s));
      const T wc = T(gauss_legendre32_weight(i)) * cosh_tau;
      sum_f = fma(wc, f(a), sum_f);
      sum_1 = sum_1 + wc;
    }
  }
  return sum_f / sum_1;
}

// ∫_H D(h) dh for anisotropic GGX (Eq. 29 averaged over azimuth, see above).
template <class T>
GLINTLAB_FN T total_area(const GGX<T>& g) {
  return total_area_azimuthal_average(g.alpha_x, g.alpha_y,
                                      [](T a) { return total_area_ggx_iso_a2(a); });
}

// ∫_H D(h) dh for anisotropic Beckmann (Eq. 30 averaged over azimuth, see above).
template <class T>
GLINTLAB_FN T total_area(const Beckmann<T>& b) {
  return total_area_azimuthal_average(b.alpha_x, b.alpha_y,
                                      [](T a) { return total_area_beckmann_iso_a2(a); });
}

}  // namespace glintlab
