// Shader-style fast math (single precision): exp by 2^n × polynomial, erf/erfc by Abramowitz &
// Stegun 7.1.26, rsqrt by the hardware estimate plus one Newton step. Used by Wide<B, FastMath>.
#pragma once

// Measured errors (tests/simd/fast_math_test.cpp, dense sweeps; it fails if an implementation
// drifts past these documented bounds; README "Fast math" has the table):
//   exp    x in [−87, 88]:  max relative error 3.0e-6 (25 ulp); results below 2^−126 flush to 0
//   erf    x in [−6, 6]:    max absolute error 2.5e-7 (A&S 7.1.26 alone: 1.5e-7)
//   erfc   x in [−6, 9.2]:  max absolute error 2.5e-7; relative error grows in the tail
//                           (erfc(x) < 1e-10): up to 2e-5 for x ≤ 4, 1e-4 for x ≤ 9
//   rsqrt  x in [2^−126, 2^127]: max relative error 4.8e-7 SSE/AVX (12-bit estimate, one Newton
//                           step); AVX-512's 14-bit estimate gives less (not measurable here)
// Only the float policy exists: these approximations are single-precision by construction.

#include <type_traits>

namespace glintlab::fast {

// e^x = 2^n · 2^f, n = round(x log2 e), f in [−½, ½]; 2^f = e^{f ln 2} by its Taylor polynomial
// of degree 6 (truncation (½ ln 2)^7/7! = 1.2e-7 relative), evaluated by Horner with fma.
template <class B>
GLINTLAB_FN B exp(const B& x) {
  using S = typename RawTraits<B>::scalar;
  static_assert(std::is_same_v<S, float>, "fast::exp is single precision");
  const B xc = raw::min(raw::max(x, B(-87.3f)), B(88.7f));
  const B t = xc * B(1.44269504088896341f);  // log2 e
  const B n = raw::round_nearest(t);
  const B g = (t - n) * B(0.693147180559945309f);  // f ln 2, |g| ≤ 0.347
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
template <class B>
GLINTLAB_FN B erf(const B& x) {
  const B ax = raw::abs(x);
  return raw::copysign(B(1.0f) - erfc_positive(ax), x);
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

}  // namespace glintlab::fast
