// Beckmann NDF→disk map T = B1⁻¹∘B2⁻¹ and its inverse and Jacobians (Kemppinen 2025 Sec. 3.2.2).
// B1 is the Marsaglia-style polar map disk → slopes, B2 the normalisation slopes → hemisphere.
#pragma once

#include "core/maps/disk_square.h"
#include "core/ndf/beckmann.h"

namespace glintlab {

// −expm1(−t)/t = (1 − e^{−t})/t, → 1 at t = 0 and → 0 at t = ∞; expm1 keeps small t exact.
template <class T>
GLINTLAB_FN T beckmann_one_minus_exp_ratio(T t) {
  const Mask<T> pos = t > T(0);
  return select(pos, -expm1(-t) / select(pos, t, T(1)), T(1));
}

// r²/(−log(1 − r²)), → 1 at r² = 0 and → 0 at r² = 1; log1p keeps small r² exact and is accurate
// near the rim.
template <class T>
GLINTLAB_FN T beckmann_log_ratio(T r2) {
  const T t = -log1p(-r2);
  const Mask<T> pos = r2 > T(0);
  return select(pos, r2 / select(pos, t, T(1)), T(1));
}

// --- Stages ------------------------------------------------------------------------------------

// B1 (Kemppinen Sec. 3.2.2): unit disk → slopes, (x, y)·√(−α² log(1 − r²)/r²), made anisotropic
// by scaling the two axes by αx and αy. A uniform point on the disk becomes a slope with the
// Beckmann density P22(s) = exp(−sx²/αx² − sy²/αy²)/(π αx αy): r² = 1 − exp(−|s/α|²) is exactly
// the radial CDF (Marsaglia's polar method with 1 − r² in place of r², which is also uniform).
template <class T>
GLINTLAB_FN Vec2<T> beckmann_b1(const Beckmann<T>& b, Vec2<T> q) {
  const T r2 = dot(q, q);
  const T k = rsqrt(beckmann_log_ratio(r2));  // √(−log(1 − r²)/r²)
  return {b.alpha_x * q.x * k, b.alpha_y * q.y * k};
}

// B1⁻¹(s) = q·√((1 − e^{−t})/t), q = (sx/αx, sy/αy), t = |q|² (written with expm1, so small
// slopes keep full relative precision).
template <class T>
GLINTLAB_FN Vec2<T> beckmann_b1_inverse(const Beckmann<T>& b, Vec2<T> s) {
  const Vec2<T> q{s.x / b.alpha_x, s.y / b.alpha_y};
  const T k = sqrt(beckmann_one_minus_exp_ratio(dot(q, q)));
  return k * q;
}

// |det dB1⁻¹/ds| = exp(−t)/(αx αy): the radial part q ↦ q·h(|q|)/|q| with h(ρ) = √(1 − e^{−ρ²})
// has determinant (h/ρ)·h′ = e^{−ρ²}, the axis scaling 1/(αx αy). (= π P22(s).)
template <class T>
GLINTLAB_FN T beckmann_b1_inverse_jacobian(const Beckmann<T>& b, Vec2<T> s) {
  const T t = sqr(s.x / b.alpha_x) + sqr(s.y / b.alpha_y);
  return exp(-t) / (b.alpha_x * b.alpha_y);
}

// B2(s) = (sx, sy, 1)/√(1 + |s|²) (Kemppinen Sec. 3.2.2): slopes → upper hemisphere.
template <class T>
GLINTLAB_FN Vec3<T> beckmann_b2(Vec2<T> s) {
  return normalize(Vec3<T>{s.x, s.y, T(1)});
}

// B2⁻¹(ω) = (ωx, ωy)/ωz (the gnomonic projection), for ωz > 0.
template <class T>
GLINTLAB_FN Vec2<T> beckmann_b2_inverse(Vec3<T> w) {
  return {w.x / w.z, w.y / w.z};
}

// |det dB2⁻¹/dω| = 1/ωz³ (slope area per steradian; the cos³θ of the slope-to-normal change).
template <class T>
GLINTLAB_FN T beckmann_b2_inverse_jacobian(Vec3<T> w) {
  return T(1) / (w.z * w.z * w.z);
}

// --- The map T and its inverse, in the unit-square convention of core/maps/disk_square.h ---------

// T(ω) = B1⁻¹(B2⁻¹(ω)), returned as (q + 1)/2. Fused so it never forms the slope, which is
// infinite at the horizon: with v = (ωx/αx, ωy/αy), n = |v|, t = n²/ωz²,
//   q = (v/ωz)·√((1 − e^{−t})/t)   where n ≤ ωz (t ≤ 1: no 0/0 at ω = +z),
//   q = (v/n)·√(1 − e^{−t})        where n > ωz (t ≥ 1: finite at ωz = 0, the rim).
// For ωz ≥ 0. In float, directions with t ≳ 17 land within one ulp of the rim (e^{−t} < 2⁻²⁴):
// the Gaussian tail is compressed exponentially, so only map_from_square round-trips there.
template <class T>
GLINTLAB_FN Vec2<T> map_to_square(const Beckmann<T>& b, Vec3<T> w) {
  const Vec2<T> v{w.x / b.alpha_x, w.y / b.alpha_y};
  const T n2 = dot(v, v);
  const T z2 = sqr(w.z);
  const Mask<T> near = n2 <= z2;  // t ≤ 1
  const Mask<T> above = z2 > T(0);
  const T t = n2 / select(above, z2, T(1));
  const T k_near = sqrt(beckmann_one_minus_exp_ratio(t)) / select(near, w.z, T(1));
  const T one_minus_e = select(above, -expm1(-t), T(1));  // 1 − e^{−t}, exactly 1 at the horizon
  const T k_far = sqrt(one_minus_e / select(near, T(1), n2));
  return disk_to_square(select(near, k_near, k_far) * v);
}

// T⁻¹(p) = B2(B1(2p − 1)), written as normalize(αx qx, αy qy, √(r²/t)), t = −log(1 − r²), which
// is B2(B1(q)) multiplied through by the finite √(r²/t): exact at the centre (→ +z) and at the
// rim (→ the horizon), where B1 itself is infinite.
template <class T>
GLINTLAB_FN Vec3<T> map_from_square(const Beckmann<T>& b, Vec2<T> p) {
  const Vec2<T> q = square_to_disk(p);
  const T r2 = min(dot(q, q), T(1));
  return normalize(Vec3<T>{b.alpha_x * q.x, b.alpha_y * q.y, sqrt(beckmann_log_ratio(r2))});
}

// The factor Kemppinen Eq. 3 uses as |J_T|: D(ω)/|U_Ω|, |U_Ω| = π/4.
template <class T>
GLINTLAB_FN T map_jacobian_paper(const Beckmann<T>& b, Vec3<T> w) {
  return b.D(w) / T(kMapDomainArea<T>);
}

// The actual |det dT/dω| of map_to_square per steradian: the product of the stage Jacobians,
// ¼ (disk→square) · e^{−t}/(αx αy) (B1⁻¹) · 1/ωz³ (B2⁻¹), t = |(ωx/αx, ωy/αy)|²/ωz²; 0 at and
// below the horizon. This equals |U_Ω|·D(ω)·ωz: T pushes D·cosθ (the projected-area density, a
// probability density) to the uniform disk, so it differs from map_jacobian_paper by the factor
// 16/(π² ωz) (≈ 1.62 at ω = +z).
template <class T>
GLINTLAB_FN T map_jacobian_true(const Beckmann<T>& b, Vec3<T> w) {
  const Mask<T> up = w.z > T(0);
  const Vec3<T> ws = select(up, w, Vec3<T>{T(0), T(0), T(1)});
  const Vec2<T> s = beckmann_b2_inverse(ws);
  const T t = sqr(s.x / b.alpha_x) + sqr(s.y / b.alpha_y);
  // The B1⁻¹ factor e^{−t}/(αx αy) is applied as two halves e^{−t/2}, one after the other factors,
  // so the result keeps its precision where e^{−t} alone would be subnormal (as in Beckmann::D).
  const T h = exp(T(-0.5) * t);
  const T j = T(kDiskToSquareJacobian<T>) * (h / (b.alpha_x * b.alpha_y)) *
              beckmann_b2_inverse_jacobian(ws) * h;
  // Where e^{−t/2} underflows to 0 the product is 0, even if 1/ωz³ has overflowed (ωz ≲ 1e-13).
  return select(up && (h > T(0)), j, T(0));
}

}  // namespace glintlab
