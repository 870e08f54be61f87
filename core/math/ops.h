// Scalar ops layer: the math every kernel calls, for float and double. SIMD (xsimd) and CUDA
// backends overload the same names for their types, so kernels never call std:: directly.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "core/math/config.h"

namespace glintlab {

template <class T>
inline constexpr Scalar<T> kPi = std::numbers::pi_v<Scalar<T>>;
template <class T>
inline constexpr Scalar<T> kInvPi = std::numbers::inv_pi_v<Scalar<T>>;

// --- Selection and masks -------------------------------------------------------------------
// select(m, a, b) = m ? a : b, evaluated without a branch on per-lane data in batch builds.
GLINTLAB_FN float select(bool m, float a, float b) { return m ? a : b; }
GLINTLAB_FN double select(bool m, double a, double b) { return m ? a : b; }
GLINTLAB_FN bool select(bool m, bool a, bool b) { return m ? a : b; }
GLINTLAB_FN bool any(bool m) { return m; }
GLINTLAB_FN bool all(bool m) { return m; }

// --- Arithmetic --------------------------------------------------------------------------------
GLINTLAB_FN float fma(float a, float b, float c) { return std::fma(a, b, c); }
GLINTLAB_FN double fma(double a, double b, double c) { return std::fma(a, b, c); }
GLINTLAB_FN float abs(float x) { return std::fabs(x); }
GLINTLAB_FN double abs(double x) { return std::fabs(x); }
GLINTLAB_FN float min(float a, float b) { return std::fmin(a, b); }
GLINTLAB_FN double min(double a, double b) { return std::fmin(a, b); }
GLINTLAB_FN float max(float a, float b) { return std::fmax(a, b); }
GLINTLAB_FN double max(double a, double b) { return std::fmax(a, b); }
GLINTLAB_FN float copysign(float a, float b) { return std::copysign(a, b); }
GLINTLAB_FN double copysign(double a, double b) { return std::copysign(a, b); }
GLINTLAB_FN float sign_not_zero(float x) { return std::copysign(1.0f, x); }
GLINTLAB_FN double sign_not_zero(double x) { return std::copysign(1.0, x); }

GLINTLAB_FN float floor(float x) { return std::floor(x); }
GLINTLAB_FN double floor(double x) { return std::floor(x); }

GLINTLAB_FN float sqrt(float x) { return std::sqrt(x); }
GLINTLAB_FN double sqrt(double x) { return std::sqrt(x); }
GLINTLAB_FN float rsqrt(float x) { return 1.0f / std::sqrt(x); }
GLINTLAB_FN double rsqrt(double x) { return 1.0 / std::sqrt(x); }

// --- Transcendentals ---------------------------------------------------------------------------
GLINTLAB_FN float exp(float x) { return std::exp(x); }
GLINTLAB_FN double exp(double x) { return std::exp(x); }
GLINTLAB_FN float expm1(float x) { return std::expm1(x); }
GLINTLAB_FN double expm1(double x) { return std::expm1(x); }
GLINTLAB_FN float log(float x) { return std::log(x); }
GLINTLAB_FN double log(double x) { return std::log(x); }
GLINTLAB_FN float log1p(float x) { return std::log1p(x); }
GLINTLAB_FN double log1p(double x) { return std::log1p(x); }
GLINTLAB_FN float erf(float x) { return std::erf(x); }
GLINTLAB_FN double erf(double x) { return std::erf(x); }
GLINTLAB_FN float erfc(float x) { return std::erfc(x); }
GLINTLAB_FN double erfc(double x) { return std::erfc(x); }
GLINTLAB_FN float sin(float x) { return std::sin(x); }
GLINTLAB_FN double sin(double x) { return std::sin(x); }
GLINTLAB_FN float cos(float x) { return std::cos(x); }
GLINTLAB_FN double cos(double x) { return std::cos(x); }
GLINTLAB_FN float tan(float x) { return std::tan(x); }
GLINTLAB_FN double tan(double x) { return std::tan(x); }
GLINTLAB_FN float atan(float x) { return std::atan(x); }
GLINTLAB_FN double atan(double x) { return std::atan(x); }
GLINTLAB_FN float atan2(float y, float x) { return std::atan2(y, x); }
GLINTLAB_FN double atan2(double y, double x) { return std::atan2(y, x); }
GLINTLAB_FN float acos(float x) { return std::acos(x); }
GLINTLAB_FN double acos(double x) { return std::acos(x); }
GLINTLAB_FN float acosh(float x) { return std::acosh(x); }
GLINTLAB_FN double acosh(double x) { return std::acosh(x); }
GLINTLAB_FN void sincos(float x, float* s, float* c) {
  *s = std::sin(x);
  *c = std::cos(x);
}
GLINTLAB_FN void sincos(double x, double* s, double* c) {
  *s = std::sin(x);
  *c = std::cos(x);
}
GLINTLAB_FN bool isfinite(float x) { return std::isfinite(x); }
GLINTLAB_FN bool isfinite(double x) { return std::isfinite(x); }

// --- Derived helpers, written once for every float type ----------------------------------------
template <class T>
GLINTLAB_FN T sqr(T x) {
  return x * x;
}
template <class T>
GLINTLAB_FN T clamp(T x, T lo, T hi) {
  return min(max(x, lo), hi);
}
template <class T>
GLINTLAB_FN T saturate(T x) {
  return clamp(x, T(0), T(1));
}
// sqrt of a quantity that is non-negative up to rounding.
template <class T>
GLINTLAB_FN T safe_sqrt(T x) {
  return sqrt(max(x, T(0)));
}
template <class T>
GLINTLAB_FN T safe_acos(T x) {
  return acos(clamp(x, T(-1), T(1)));
}
// a / b, with 0 where b == 0 (a measure-zero set the kernels must not turn into NaN).
template <class T>
GLINTLAB_FN T safe_div(T a, T b) {
  const Mask<T> zero = b == T(0);
  return select(zero, T(0), a / select(zero, T(1), b));
}

// Inverse error function. Giles, "Approximating the erfinv function" (GPU Gems Pro 2010), single-
// precision polynomial as the start, then Newton steps (see below) to reach the precision of T.
// Valid for y in (-1, 1); returns +-inf at +-1.
template <class T>
GLINTLAB_FN T erfinv(T y) {
  T w = -log((T(1) - y) * (T(1) + y));
  const Mask<T> central = w < T(5);
  const T wc = w - T(2.5);
  T pc = T(2.81022636e-08);
  pc = fma(pc, wc, T(3.43273939e-07));
  pc = fma(pc, wc, T(-3.5233877e-06));
  pc = fma(pc, wc, T(-4.39150654e-06));
  pc = fma(pc, wc, T(0.00021858087));
  pc = fma(pc, wc, T(-0.00125372503));
  pc = fma(pc, wc, T(-0.00417768164));
  pc = fma(pc, wc, T(0.246640727));
  pc = fma(pc, wc, T(1.50140941));
  const T wt = sqrt(max(w, T(0))) - T(3);
  T pt = T(-0.000200214257);
  pt = fma(pt, wt, T(0.000100950558));
  pt = fma(pt, wt, T(0.00134934322));
  pt = fma(pt, wt, T(-0.00367342844));
  pt = fma(pt, wt, T(0.00573950773));
  pt = fma(pt, wt, T(-0.0076224613));
  pt = fma(pt, wt, T(0.00943887047));
  pt = fma(pt, wt, T(1.00167406));
  pt = fma(pt, wt, T(2.83297682));
  T x = select(central, pc, pt) * y;
  // Newton on f(x) = erf(x) - y, f'(x) = 2/sqrt(pi) exp(-x^2).
  const T k = T(0.886226925452758013649);  // sqrt(pi)/2
  // For |y| > ½ Newton runs on log erfc|x| = log(1 − |y|) instead: 1 − |y| is exact there and erfc
  // keeps relative precision, whereas erf(x) − y has lost its digits near ±1; in log form the
  // equation is nearly linear in x², so the float-accurate start converges in double too, up to
  // |y| = 1 − 2⁻⁵³. The start is single-precision accurate only for 1 − |y| ≳ 2⁻²⁸, so double
  // takes four steps (two leave ~1e10 ulp at 1 − |y| = 2⁻⁵¹); float's range needs two.
  const Mask<T> tail = abs(y) > T(0.5);
  const T log_r = log(T(1) - abs(y));
  constexpr int kSteps = sizeof(Scalar<T>) > 4 ? 4 : 2;
  for (int i = 0; i < kSteps; ++i) {
    const T e = exp(x * x);
    const T c = erfc(abs(x));
    const T step_tail = sign_not_zero(y) * (log_r - log(c)) * k * e * c;
    const T step = select(tail, step_tail, (erf(x) - y) * k * e);
    x = x - select(isfinite(step), step, T(0));
  }
  return x;
}

// exp(−x²) without the rounding of x²: x² = p + e exactly (fma), exp(−p)(1 − e). The plain form
// has a relative error of about x²·ε, which differences of exponentials then amplify.
template <class T>
GLINTLAB_FN T exp_neg_sqr(T x) {
  const T p = x * x;
  const T e = fma(x, x, -p);
  return exp(-p) * (T(1) - e);
}

// Scaled complementary error function erfcx(x) = exp(x²) erfc(x), for x ≥ 0 (finite for x < 0
// until exp(x²) overflows). For x < 8: exp(x²) erfc(x) with x² split exactly as p + e (fma), so
// the argument of exp is not rounded: exp(p)(1 + e) erfc(x), a few ulp. For x ≥ 8: the asymptotic
// series (1/(x√π)) Σ_k (−1)^k (2k−1)!!/(2x²)^k to k = 16 (first omitted term < 1e-17 at x = 8),
// so the product never overflows (exp(x²) would past x ≈ 9.4 in float, 26.6 in double).
template <class T>
GLINTLAB_FN T erfcx(T x) {
  const Mask<T> large = x >= T(8);
  const T p = x * x;
  const T e = fma(x, x, -p);
  const T direct = exp(select(large, T(0), p)) * (T(1) + e) * erfc(x);
  const T xl = select(large, x, T(8));
  const T y = T(0.5) / (xl * xl);
  T s = T(1);
  for (int k = 16; k >= 1; --k) s = fma(-T(2 * k - 1) * y, s, T(1));
  const T asym = s * T(0.56418958354775628695) / xl;  // 1/√π
  return select(large, asym, direct);
}

}  // namespace glintlab
