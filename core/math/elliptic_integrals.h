// Elliptic integrals for kernels: Carlson's symmetric R_F and R_D by the duplication theorem
// (Carlson 1995, "Numerical computation of real or complex elliptic integrals", Numer. Algorithms
// 10, Sec. 2, Alg. 1–2; NIST DLMF 19.36.1), and the Legendre forms K, E, F(φ, k), E(φ, k) through
// them (DLMF 19.25.1, 19.25.5). A fixed number of duplication steps, no branches, ops layer only.
#pragma once

#include "core/math/ops.h"

namespace glintlab {

// Duplication steps: each divides the spread of (x, y, z) by 4, so after n steps the first
// neglected term of the expansion about the mean is ~ 4^(−2n) relative: 14 steps reach double
// precision (measured against Boost.Math to 1e-14 in tests/core/math); float shares the loop.
// Near k = 1, forming 1 − k² from k loses digits before any integral is taken: callers with k'
// at hand (the disk light) pass k'² to carlson_rf/carlson_rd directly.
inline constexpr int kCarlsonSteps = 14;

// R_F(x, y, z) = ½ ∫ dt / √((t + x)(t + y)(t + z)), x, y, z ≥ 0, at most one zero.
template <class T>
GLINTLAB_FN T carlson_rf(T x, T y, T z) {
  for (int i = 0; i < kCarlsonSteps; ++i) {
    const T sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    const T l = sx * sy + sy * sz + sz * sx;
    x = T(0.25) * (x + l);
    y = T(0.25) * (y + l);
    z = T(0.25) * (z + l);
  }
  // The fifth-order expansion about the mean A (DLMF 19.36.1).
  const T a = (x + y + z) / T(3);
  const T dx = T(1) - x / a, dy = T(1) - y / a, dz = -(dx + dy);
  const T e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
  return (T(1) - e2 / T(10) + e3 / T(14) + e2 * e2 / T(24) - T(3) * e2 * e3 / T(44)) * rsqrt(a);
}

// R_D(x, y, z) = (3/2) ∫ dt / ((t + z) √((t + x)(t + y)(t + z))), x, y ≥ 0 (at most one zero),
// z > 0.
template <class T>
GLINTLAB_FN T carlson_rd(T x, T y, T z) {
  T sum = T(0), fac = T(1);
  for (int i = 0; i < kCarlsonSteps; ++i) {
    const T sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    const T l = sx * sy + sy * sz + sz * sx;
    sum = sum + fac / (sz * (z + l));
    fac = T(0.25) * fac;
    x = T(0.25) * (x + l);
    y = T(0.25) * (y + l);
    z = T(0.25) * (z + l);
  }
  const T a = (x + y + T(3) * z) / T(5);
  const T dx = T(1) - x / a, dy = T(1) - y / a, dz = (dx + dy) / T(-3);
  const T ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - T(6) * eb, ee = ed + ec + ec;
  const T s = T(1) + ed * (T(-3) / T(14) + T(9) / T(88) * ed - T(9) / T(52) * dz * ee) +
              dz * (ee / T(6) + dz * (T(-9) / T(22) * ec + dz * T(3) / T(26) * ea));
  return T(3) * sum + fac * s * rsqrt(a) / a;
}

// Complete integrals of modulus k (not parameter m = k²), 0 ≤ k < 1 (DLMF 19.25.1).
template <class T>
GLINTLAB_FN T elliptic_k(T k) {
  return carlson_rf(T(0), T(1) - k * k, T(1));
}
template <class T>
GLINTLAB_FN T elliptic_e(T k) {
  const T m = k * k;
  return carlson_rf(T(0), T(1) - m, T(1)) - m / T(3) * carlson_rd(T(0), T(1) - m, T(1));
}

// Incomplete integrals F(φ, k), E(φ, k) for 0 ≤ φ ≤ π/2 (DLMF 19.25.5).
template <class T>
GLINTLAB_FN T elliptic_f(T phi, T k) {
  T s, c;
  sincos(phi, &s, &c);
  return s * carlson_rf(c * c, T(1) - k * k * s * s, T(1));
}
template <class T>
GLINTLAB_FN T elliptic_e(T phi, T k) {
  T s, c;
  sincos(phi, &s, &c);
  const T d = T(1) - k * k * s * s;
  return s * carlson_rf(c * c, d, T(1)) - k * k * s * s * s / T(3) * carlson_rd(c * c, d, T(1));
}

}  // namespace glintlab
