// Shader-style fast math (single precision): exp by 2^n × polynomial, erf/erfc by Abramowitz &
// Stegun 7.1.26, rsqrt by the hardware estimate plus one Newton step, GGX D with one division
// (Heitz 2014 Eq. 85). Used by Wide<B, FastMath>.
#pragma once

// Errors, measured by tests/simd/fast_math_test.cpp over 4·10^6 evenly spaced points of each
// range against the double-precision libm (the test fails if an implementation exceeds these
// documented bounds; docs/simd.md "Fast math" has the table):
//   exp    x in [−87, 88]:   relative ≤ 2.5e-7 (3 ulp); results below 2^−126 flush to 0
//   erf    x in [−6, 6]:     absolute ≤ 3.5e-7, relative ≤ 6.5e-7 (6 ulp)
//   erfc   x in [−6, 9.2]:   absolute ≤ 6e-7; relative ≤ 3e-3 for x ≤ 4, ≤ 3e-2 for x ≤ 9.2 (the
//                            A&S form bounds the absolute error only: the far tail is coarse)
//   rsqrt  x in [1e-3, 1e3]: relative ≤ 3.5e-7 (3 ulp), from the estimate's specification, not
//                            from one CPU: the SSE/AVX estimate is CPU-specific, |e| ≤ 1.5·2^−12
//                            (Intel SDM, RSQRTPS), so one Newton step leaves 1.5e² ≤ 2.01e-7,
//                            plus ≤ 1.5e-7 from its three float roundings. Measured: 1.9e-7 on an
//                            AMD EPYC, 2.4e-7 on an Intel Xeon; AVX-512's estimate has
//                            |e| ≤ 2^−14 (tests/simd/avx512_ops_test.cpp prints each ISA's error)
//   ggx_d  the kernel inputs of core/simd/inputs.h (α in [1e-3, 2], anisotropy to 1:1000, m
//          NDF-drawn, hemisphere and sphere) against GGX<double>::D: relative ≤ 1e-6, ≤ 16 ulp
//          (the test's 10^6 rows: 7.4e-7, 11 ulp; 4·10^6 other rows: 8.0e-7, 12 ulp, where the
//          exact float form has 6.6e-7, 10 ulp)
// Only a float policy exists: these approximations are single precision by construction.
#include <type_traits>

namespace glintlab::fast {

inline constexpr double kFastExpMaxRel = 2.5e-7;
inline constexpr double kFastErfMaxAbs = 3.5e-7;
inline constexpr double kFastErfMaxRel = 6.5e-7;
inline constexpr double kFastErfcMaxAbs = 6e-7;
inline constexpr double kFastErfcMaxRelTo4 = 3e-3;
inline constexpr double kFastErfcMaxRelTo9 = 3e-2;
inline constexpr double kFastRsqrtMaxRel = 3.5e-7;
inline constexpr double kFastGgxDMaxRel = 1e-6;
inline constexpr int kFastGgxDMaxUlp = 16;

// e^x = 2^n e^g, n = round(x log2 e), |g| ≤ ½ ln 2; e^g by its Taylor polynomial of degree 6
// (truncation (½ ln 2)^7/7! = 1.2e-7 relative), evaluated by Horner with fma.
template <class B>
GLINTLAB_FN B exp(const B& x) {
  using S = typename RawTraits<B>::scalar;
  static_assert(std::is_same_v<S, float>, "fast::exp is single precision");
  const B xc = raw::min(raw::max(x, B(-87.3f)), B(88.7f));
  const B n = raw::round_nearest(xc * B(1.44269504088896341f));  // log2 e
  // g = x − n ln 2 in two fma steps (Cody & Waite 1980's split of ln 2): forming x log2 e − n
  // instead would carry the rounding of x log2 e, up to 7.5e-6 relative at |x| = 87.
  B g = raw::fma(-n, B(0.693145751953125f), xc);       // ln 2 high part, exact in 12 bits
  g = raw::fma(-n, B(1.42860682030941723212e-6f), g);  // ln 2 − high part; |g| ≤ 0.347
  B p = B(1.0f / 720.0f);
  p = raw::fma(p, g, B(1.0f / 120.0f));
  p = raw::fma(p, g, B(1.0f / 24.0f));
  p = raw::fma(p, g, B(1.0f / 6.0f));
  p = raw::fma(p, g, B(0.5f));
  p = raw::fma(p, g, B(1.0f));
  p = raw::fma(p, g, B(1.0f));
  // n ≥ −126 keeps the exponent field normal; below that e^x < 2^−126 is flushed to 0.
  const B r = p * raw::pow2_int(raw::max(n, B(-126.0f)));
  return raw::select(x < B(-87.3f), B(0.0f), r);
}

// erf by Abramowitz & Stegun 7.1.26: 1 − t(a1 + t(a2 + … + t a5)) e^{−x²}, t = 1/(1 + p|x|),
// |error| ≤ 1.5e-7 in exact arithmetic; here with fast::exp.
template <class B>
GLINTLAB_FN B erfc_positive(const B& ax) {
  const B t = B(1.0f) / raw::fma(B(0.3275911f), ax, B(1.0f));
  B p = B(1.061405429f);
  p = raw::fma(p, t, B(-1.453152027f));
  p = raw::fma(p, t, B(1.421413741f));
  p = raw::fma(p, t, B(-0.284496736f));
  p = raw::fma(p, t, B(0.254829592f));
  return p * t * fast::exp(-(ax * ax));
}
// Near 0, 1 − erfc loses all relative precision (A&S alone: 15 % at x = 1e-6), so |x| < ½ takes
// the Maclaurin series 2/√π Σ (−1)^n x^{2n+1}/(n!(2n+1)) to n = 5 (next term < 1.2e-8 there).
template <class B>
GLINTLAB_FN B erf(const B& x) {
  const B ax = raw::abs(x);
  const B x2 = x * x;
  B p = B(-1.0f / 1320.0f);
  p = raw::fma(p, x2, B(1.0f / 216.0f));
  p = raw::fma(p, x2, B(-1.0f / 42.0f));
  p = raw::fma(p, x2, B(1.0f / 10.0f));
  p = raw::fma(p, x2, B(-1.0f / 3.0f));
  p = raw::fma(p, x2, B(1.0f));
  const B series = B(1.12837916709551257f) * x * p;  // 2/√π
  const B tail = raw::copysign(B(1.0f) - erfc_positive(ax), x);
  return raw::select(ax < B(0.5f), series, tail);
}
template <class B>
GLINTLAB_FN B erfc(const B& x) {
  const B c = erfc_positive(raw::abs(x));
  return raw::select(x < B(0.0f), B(2.0f) - c, c);
}

// 1/√x: hardware estimate y0, one Newton step y0 (3 − x y0²)/2 (doubles the bits: 12 → ~23).
template <class B>
GLINTLAB_FN B rsqrt(const B& x) {
  const B y = raw::rsqrt_estimate(x);
  return y * raw::fma(B(-0.5f) * x, y * y, B(1.5f));
}

// GGX D (Heitz 2014 Eq. 85) with one division instead of three: with q = αx αy and
// e' = (mx αy)² + (my αx)² + (mz q)² = q² (mx²/αx² + my²/αy² + mz²), D = q t² / π, t = q / e'.
// On this CPU the divider bounds the exact form (three divisions per row; a 256-bit division
// costs two 128-bit ones, docs/simd.md "Speed-ups"), so this form is ~2× faster. Plain × and + (no
// fma): the SSE4.2 build emulates fma through double, which would cost more than the division.
// Every term of e' is ≥ 0, so there is no cancellation; for α ≥ 1e-3, q² ≥ 1e-12 keeps e' normal.
template <class B>
GLINTLAB_FN B ggx_d(const B& ax, const B& ay, const B& mx, const B& my, const B& mz) {
  const B q = ax * ay;
  const B u = mx * ay;
  const B v = my * ax;
  const B w = mz * q;
  const B e = u * u + v * v + w * w;
  const B t = q / e;
  const B d = (B(0.318309886183790671538f) * q) * (t * t);  // 1/π
  return raw::select(mz > B(0.0f), d, B(0.0f));
}

}  // namespace glintlab::fast
