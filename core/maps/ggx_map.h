// GGX NDF→disk map T = L∘M̃ and its inverse and Jacobians (Kemppinen 2025 Sec. 3.2.1, Eq. 3, 6, 7).
// M̃ is the Eq. 6 stretch, L Lambert's projection (Eq. 7); both Eq. 6 as printed and the true
// Jacobian are exposed.
#pragma once

#include "core/maps/disk_square.h"
#include "core/ndf/ggx.h"

namespace glintlab {

// --- Stages ------------------------------------------------------------------------------------

// M̃(ω) = Mᵀω/‖Mᵀω‖ (Kemppinen Eq. 6) with M = diag(1/αx, 1/αy, 1): the GGX normal of roughness
// (αx, αy) is the stretched normal normalize(αx ux, αy uy, uz) of the α = 1 (uniform) hemisphere
// normal u, and D_GGX(ω) = |M|/(π‖Mᵀω‖⁴), so M̃ takes the GGX configuration to the uniform one.
// Computed as normalize(ωx αy, ωy αx, ωz αx αy) = normalize(αx αy Mᵀω): no division, no overflow.
template <class T>
GLINTLAB_FN Vec3<T> ggx_stretch(const GGX<T>& g, Vec3<T> w) {
  return normalize(Vec3<T>{w.x * g.alpha_y, w.y * g.alpha_x, w.z * (g.alpha_x * g.alpha_y)});
}

// M̃⁻¹(u) = normalize(αx ux, αy uy, uz).
template <class T>
GLINTLAB_FN Vec3<T> ggx_unstretch(const GGX<T>& g, Vec3<T> u) {
  return normalize(Vec3<T>{g.alpha_x * u.x, g.alpha_y * u.y, u.z});
}

// ‖Mᵀω‖² = ωx²/αx² + ωy²/αy² + ωz², the same quadratic form as in GGX<T>::D.
template <class T>
GLINTLAB_FN T ggx_stretch_norm2(const GGX<T>& g, Vec3<T> w) {
  return sqr(w.x / g.alpha_x) + sqr(w.y / g.alpha_y) + sqr(w.z);
}

// |J_M̃| as printed in Kemppinen Eq. 6: |M|/‖Mᵀω‖⁴ (= π D_GGX(ω)).
template <class T>
GLINTLAB_FN T ggx_stretch_jacobian_eq6(const GGX<T>& g, Vec3<T> w) {
  const T e = ggx_stretch_norm2(g, w);
  return T(1) / (g.alpha_x * g.alpha_y * e * e);
}

// The true solid-angle Jacobian of M̃ at a unit ω: for ω ↦ Aω/‖Aω‖ on the sphere it is
// |det A|/‖Aω‖³ (the cube, not the fourth power: the extra 1/‖Aω‖ of Eq. 6 is the cosine change
// that turns D into the projected-area density D·cosθ). Checked against finite differences in
// tests/core/maps/ggx_map_test.cpp.
template <class T>
GLINTLAB_FN T ggx_stretch_jacobian_true(const GGX<T>& g, Vec3<T> w) {
  const T e = ggx_stretch_norm2(g, w);
  return T(1) / (g.alpha_x * g.alpha_y * e * sqrt(e));
}

// Lambert's azimuthal projection L(x, y, z) = (x, y)/√(1 + z) (Kemppinen Eq. 7): the upper
// hemisphere onto the unit disk. It is the equal-area Lambert map √(2/(1+z))·(x, y) scaled by
// 1/√2, so its Jacobian is the constant ½ (area 2π onto area π).
template <class T>
GLINTLAB_FN Vec2<T> lambert_to_disk(Vec3<T> u) {
  const T s = rsqrt(T(1) + u.z);
  return {u.x * s, u.y * s};
}

template <class T>
inline constexpr Scalar<T> kLambertJacobian = Scalar<T>(0.5);

// L⁻¹(q) = (q √(2 − r²), 1 − r²), r = |q| (clamped to the disk so rounding cannot make it NaN).
template <class T>
GLINTLAB_FN Vec3<T> lambert_from_disk(Vec2<T> q) {
  const T r2 = min(dot(q, q), T(1));
  const T s = sqrt(T(2) - r2);
  return {q.x * s, q.y * s, T(1) - r2};
}

// --- The map T and its inverse, in the unit-square convention of core/maps/disk_square.h ---------

// T(ω) = L(M̃(ω)) (Kemppinen Sec. 3.2.1), returned as (q + 1)/2 ∈ the disk of radius ½ at (½, ½).
// For ωz ≥ 0; ω = +z maps to the centre, the horizon to the rim.
template <class T>
GLINTLAB_FN Vec2<T> map_to_square(const GGX<T>& g, Vec3<T> w) {
  return disk_to_square(lambert_to_disk(ggx_stretch(g, w)));
}

// T⁻¹(p) = M̃⁻¹(L⁻¹(2p − 1)).
template <class T>
GLINTLAB_FN Vec3<T> map_from_square(const GGX<T>& g, Vec2<T> p) {
  return ggx_unstretch(g, lambert_from_disk(square_to_disk(p)));
}

// The factor Kemppinen Eq. 3 uses as |J_T|: D(ω)/|U_Ω|, |U_Ω| = π/4.
template <class T>
GLINTLAB_FN T map_jacobian_paper(const GGX<T>& g, Vec3<T> w) {
  return g.D(w) / T(kMapDomainArea<T>);
}

// The actual |det dT/dω| of map_to_square per steradian of ω: the product of the stage Jacobians,
// ¼ (disk→square) · ½ (Lambert) · |M|/‖Mᵀω‖³ (M̃) = 1/(8 αx αy ‖Mᵀω‖³).
// It differs from map_jacobian_paper by the factor 32/(π² ‖Mᵀω‖) (≈ 3.24 at ω = +z), i.e. it is
// not proportional to D: a uniform point on U_Ω pulled back by T has density D(ω)‖Mᵀω‖/2 in ω.
template <class T>
GLINTLAB_FN T map_jacobian_true(const GGX<T>& g, Vec3<T> w) {
  return T(kDiskToSquareJacobian<T>) * T(kLambertJacobian<T>) * ggx_stretch_jacobian_true(g, w);
}

}  // namespace glintlab
