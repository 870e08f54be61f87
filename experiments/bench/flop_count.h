// Counted<T>: a float type that counts the operations a kernel performs, for the roofline.
#pragma once

// Kernels are templates on their float type, so instantiating one on Counted counts exactly the
// ops its branch-free code executes per evaluation (every select evaluates both sides, as the
// SIMD lanes do). Convention: +, −, ×, ÷, √, min, max, |x|, copysign count 1 FLOP, fma 2;
// comparisons and selects are not FLOPs. Transcendentals count as the FLOPs of a typical
// vectorized polynomial implementation (xsimd's, by inspection of its range reduction + Horner
// degree): exp 12, expm1 15, log 15, log1p 17, erf/erfc 25, sin/cos 15, sincos 20, tan 20,
// atan 20, atan2 25, acos 20, acosh 20.

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "core/math/ops.h"

namespace glintlab::bench {

struct FlopCounter {
  std::uint64_t flops = 0;
};
inline thread_local FlopCounter g_flops;

struct Counted {
  double v = 0;
  Counted() = default;
  template <class U>
  requires std::is_arithmetic_v<U>
  explicit Counted(U x) : v(static_cast<double>(x)) {}
  static Counted make(double x, int cost) {
    g_flops.flops += static_cast<std::uint64_t>(cost);
    Counted c;
    c.v = x;
    return c;
  }
  friend Counted operator+(Counted a, Counted b) { return make(a.v + b.v, 1); }
  friend Counted operator-(Counted a, Counted b) { return make(a.v - b.v, 1); }
  friend Counted operator*(Counted a, Counted b) { return make(a.v * b.v, 1); }
  friend Counted operator/(Counted a, Counted b) { return make(a.v / b.v, 1); }
  friend Counted operator-(Counted a) { return make(-a.v, 0); }
  Counted& operator+=(Counted b) { return *this = *this + b; }
  Counted& operator-=(Counted b) { return *this = *this - b; }
  Counted& operator*=(Counted b) { return *this = *this * b; }
  friend bool operator<(Counted a, Counted b) { return a.v < b.v; }
  friend bool operator<=(Counted a, Counted b) { return a.v <= b.v; }
  friend bool operator>(Counted a, Counted b) { return a.v > b.v; }
  friend bool operator>=(Counted a, Counted b) { return a.v >= b.v; }
  friend bool operator==(Counted a, Counted b) { return a.v == b.v; }
  friend bool operator!=(Counted a, Counted b) { return a.v != b.v; }
};

inline Counted select(bool m, Counted a, Counted b) { return m ? a : b; }
inline Counted fma(Counted a, Counted b, Counted c) {
  return Counted::make(std::fma(a.v, b.v, c.v), 2);
}
inline Counted min(Counted a, Counted b) { return Counted::make(std::fmin(a.v, b.v), 1); }
inline Counted max(Counted a, Counted b) { return Counted::make(std::fmax(a.v, b.v), 1); }
inline Counted copysign(Counted a, Counted b) { return Counted::make(std::copysign(a.v, b.v), 1); }
inline Counted sign_not_zero(Counted a) { return Counted::make(std::copysign(1.0, a.v), 1); }
inline Counted atan2(Counted y, Counted x) { return Counted::make(std::atan2(y.v, x.v), 25); }
inline Counted rsqrt(Counted x) { return Counted::make(1.0 / std::sqrt(x.v), 2); }
inline void sincos(Counted x, Counted* s, Counted* c) {
  *s = Counted::make(std::sin(x.v), 20);
  *c = Counted::make(std::cos(x.v), 0);
}
inline bool isfinite(Counted x) { return std::isfinite(x.v); }
#define GLINTLAB_COUNTED_UNARY(name, cost) \
  inline Counted name(Counted x) { return Counted::make(std::name(x.v), cost); }
GLINTLAB_COUNTED_UNARY(sqrt, 1)
GLINTLAB_COUNTED_UNARY(exp, 12)
GLINTLAB_COUNTED_UNARY(expm1, 15)
GLINTLAB_COUNTED_UNARY(log, 15)
GLINTLAB_COUNTED_UNARY(log1p, 17)
GLINTLAB_COUNTED_UNARY(erf, 25)
GLINTLAB_COUNTED_UNARY(erfc, 25)
GLINTLAB_COUNTED_UNARY(sin, 15)
GLINTLAB_COUNTED_UNARY(cos, 15)
GLINTLAB_COUNTED_UNARY(tan, 20)
GLINTLAB_COUNTED_UNARY(atan, 20)
GLINTLAB_COUNTED_UNARY(acos, 20)
GLINTLAB_COUNTED_UNARY(acosh, 20)
#undef GLINTLAB_COUNTED_UNARY
inline Counted abs(Counted x) { return Counted::make(std::fabs(x.v), 1); }

}  // namespace glintlab::bench

namespace glintlab {
template <>
struct ScalarOf<bench::Counted> {
  using type = double;
};
}  // namespace glintlab
