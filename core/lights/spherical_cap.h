// A spherical cap of half-angle γ about an axis: solid angle 2π(1 − cos γ) (Kneiphof & Klein 2024
// Sec. 5, |Ω_i| before Eq. 20), uniform sampling and its density (the uniform cone, e.g. Pharr et
// al., PBRT 4th ed. Sec. A.5.4). Shared by the point light with a radius and the directional light.
#pragma once

#include "core/lights/light_sample.h"
#include "core/math/orthonormal_basis.h"

namespace glintlab {

// The cap is kept as 1 − cos γ, not cos γ: for the sun (γ ≈ 0.27°) 1 − cos γ ≈ 1e-5 would lose
// all but two digits in float if formed as a difference.
template <class T>
struct SphericalCap {
  Vec3<T> axis;     // unit
  T one_minus_cos;  // 1 − cos γ, in (0, 1] for γ in (0, 90°]
};

// 1 − cos γ = 2 sin²(γ/2), without cancellation.
template <class T>
GLINTLAB_FN T one_minus_cos(T gamma) {
  return T(2) * sqr(sin(T(0.5) * gamma));
}

// |Ω| = 2π(1 − cos γ) (Kneiphof & Klein 2024 Sec. 5, used in Eq. 20).
template <class T>
GLINTLAB_FN T cap_solid_angle(const SphericalCap<T>& cap) {
  return T(2 * kPi<T>) * cap.one_minus_cos;
}

// w in the cap: 1 − w·a ≤ 1 − cos γ, with 1 − w·a = |w − a|²/2 for unit vectors (exact, no
// cancellation for the tiny caps of sun-like lights).
template <class T>
GLINTLAB_FN Mask<T> cap_contains(const SphericalCap<T>& cap, Vec3<T> w) {
  const Vec3<T> d = w - cap.axis;
  return T(0.5) * dot(d, d) <= cap.one_minus_cos;
}

// Uniform density 1/|Ω| on the cap, 0 outside.
template <class T>
GLINTLAB_FN T cap_pdf(const SphericalCap<T>& cap, Vec3<T> w) {
  return select(cap_contains(cap, w), T(1) / cap_solid_angle(cap), T(0));
}

// Uniform direction in the cap: 1 − cos θ = u1 (1 − cos γ), φ = 2π u2 (inverse CDF of the uniform
// cone), with sin θ = √(x(2 − x)) for x = 1 − cos θ so small caps keep their precision.
template <class T>
GLINTLAB_FN Vec3<T> sample_cap(const SphericalCap<T>& cap, Vec2<T> u) {
  const T x = u.x * cap.one_minus_cos;
  const T sin_theta = safe_sqrt(x * (T(2) - x));
  T sp, cp;
  sincos(T(2 * kPi<T>) * u.y, &sp, &cp);
  const OrthonormalBasis<T> b = basis_from_z(cap.axis);
  return b.to_world(Vec3<T>{sin_theta * cp, sin_theta * sp, T(1) - x});
}

}  // namespace glintlab
