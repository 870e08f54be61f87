// The analytic compensation of Kemppinen et al. 2025 Sec. 3.3.4, Eq. 9–10: Gaussian mass over
// rectangles by erf, with the exact erf or a fast rational approximation (the paper's "simple
// rational polynomial approximation"), and the square-minus-neighbourhood integral of Eq. 10.
#pragma once

#include "core/math/lanes.h"
#include "core/math/vec.h"

namespace glintlab::kemppinen2025 {

enum class Erf { kExact = 0, kRational = 1 };

// erf by Abramowitz & Stegun 7.1.28, 1 − (1 + a1 x + … + a6 x⁶)^−16 for x ≥ 0 (odd extension):
// rational, no exp, |error| ≤ 3e-7 (A&S). The ^−16 is four squarings of the reciprocal.
template <class T>
GLINTLAB_FN T erf_rational(T x) {
  const T ax = abs(x);
  T p = T(0.0000430638);
  p = fma(p, ax, T(0.0002765672));
  p = fma(p, ax, T(0.0001520143));
  p = fma(p, ax, T(0.0092705272));
  p = fma(p, ax, T(0.0422820123));
  p = fma(p, ax, T(0.0705230784));
  p = fma(p, ax, T(1));
  T r = T(1) / p;
  r = r * r;
  r = r * r;
  r = r * r;
  r = r * r;
  return copysign(T(1) - r, x);
}

template <class T>
GLINTLAB_INLINE T erf_variant(T x, Erf variant) {
  return variant == Erf::kExact ? erf(x) : erf_rational(x);
}

// ∫_{a}^{b} of the 1D normal density centred at m with standard deviation s:
// ½ (erf((b − m)/(√2 s)) − erf((a − m)/(√2 s))). Returns 0 for an empty interval (b ≤ a).
template <class T>
GLINTLAB_FN T gaussian_interval_mass(T a, T b, T m, T s, Erf variant) {
  const T k = T(0.70710678118654752440) / s;
  const T v = T(0.5) * (erf_variant((b - m) * k, variant) - erf_variant((a - m) * k, variant));
  return select(b > a, max(v, T(0)), T(0));
}

// gaussian_interval_mass of one normal over [0, 1] (`whole`) and over [a, b] (`part`), bit for bit,
// an erf that both need (a = 0 or b = 1 in every lane: B(k) at the square's edge, or all of it)
// computed once.
template <class T>
struct UnitAndPartMass {
  T whole, part;
};

template <class T>
GLINTLAB_FN UnitAndPartMass<T> unit_and_part_mass(T a, T b, T m, T s, Erf variant) {
  const T k = T(0.70710678118654752440) / s;
  const T e0 = erf_variant((T(0) - m) * k, variant);
  const T e1 = erf_variant((T(1) - m) * k, variant);
  // The callers' bounds are quotients of non-negative integers (a zero is +0), so a == 0 and
  // b == 1 are the same bits as the whole's bounds.
  const T ea = any_lane<T>(!(a == T(0))) ? erf_variant((a - m) * k, variant) : e0;
  const T eb = any_lane<T>(!(b == T(1))) ? erf_variant((b - m) * k, variant) : e1;
  const T whole = T(0.5) * (e1 - e0);
  const T part = T(0.5) * (eb - ea);
  return {select(T(1) > T(0), max(whole, T(0)), T(0)), select(b > a, max(part, T(0)), T(0))};
}

// Mass of the axis-aligned normal N(m, diag(sx², sy²)) over the rectangle [lo, hi] (separable).
template <class T>
GLINTLAB_FN T gaussian_rect_mass(Vec2<T> lo, Vec2<T> hi, Vec2<T> m, Vec2<T> s, Erf variant) {
  return gaussian_interval_mass(lo.x, hi.x, m.x, s.x, variant) *
         gaussian_interval_mass(lo.y, hi.y, m.y, s.y, variant);
}

// Eq. 10: C(ω, α★) ≈ ∫_□ N − ∫_{□∩B(k)} N, the lobe at x_a over the unit square that holds U_Ω
// minus its part over the angular neighbourhood B(k) = [b_lo, b_hi] (already clipped to □). The
// printed Eq. 9 integrates over U_Ω \ B(k); Eq. 10 replaces U_Ω by □, which adds the lobe's mass
// outside the disk (Sec. 5: "considers areas outside of U_Ω", Fig. 14 left).
template <class T>
GLINTLAB_FN T compensation(Vec2<T> x_a, Vec2<T> sigma_a, Vec2<T> b_lo, Vec2<T> b_hi, Erf variant) {
  // gaussian_rect_mass over □ and over B(k), their shared erfs computed once.
  const UnitAndPartMass<T> mx = unit_and_part_mass(b_lo.x, b_hi.x, x_a.x, sigma_a.x, variant);
  const UnitAndPartMass<T> my = unit_and_part_mass(b_lo.y, b_hi.y, x_a.y, sigma_a.y, variant);
  const T whole = mx.whole * my.whole;
  const T near = mx.part * my.part;
  return max(whole - near, T(0));
}

}  // namespace glintlab::kemppinen2025
