// Wide<B, Math>: the float type kernels are instantiated on for SIMD (B = xsimd::batch) and for
// the fast-math policy (B = float too); the ops layer of core/math/ops.h overloaded for it.
#pragma once

// Why a glintlab-owned wrapper rather than xsimd::batch itself: kernels call ops unqualified
// (exp(x), select(m, a, b)), which two-phase lookup resolves at the template's definition (only
// overloads declared before it) plus argument-dependent lookup at instantiation. For a bare
// xsimd::batch ADL looks only in namespace xsimd, so which function a kernel gets would depend on
// include order, silently (xsimd::exp, xsimd::min with other NaN rules, the unfused xsimd::fma of
// SSE4.2). Wide<B, M> lives in glintlab, so ADL always finds the overloads below, whatever order
// headers come in; xsimd's own functions cannot bind to a Wide (no conversion to batch), so they
// never compete. The math policy M (ExactMath, FastMath) rides along in the type, so one kernel
// template yields both the exact and the fast instantiation.

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "core/math/lanes.h"
#include "core/math/ops.h"
#include "core/simd/xsimd.h"

#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace glintlab {

// Element and mask type of a raw register type: float/double (bool) or an xsimd batch.
template <class B>
struct RawTraits;
template <>
struct RawTraits<float> {
  using scalar = float;
  using mask = bool;
  static constexpr std::size_t kLanes = 1;
};
template <>
struct RawTraits<double> {
  using scalar = double;
  using mask = bool;
  static constexpr std::size_t kLanes = 1;
};
template <class S, class A>
struct RawTraits<xsimd::batch<S, A>> {
  using scalar = S;
  using mask = xsimd::batch_bool<S, A>;
  static constexpr std::size_t kLanes = xsimd::batch<S, A>::size;
};

// Whether xsimd's fma for architecture A is a fused instruction (FMA3; AVX-512 through the
// correction in core/simd/xsimd.h) or the unfused a*b + c it falls back to (SSE4.2): the kernels
// use fma for error-free products (exp_neg_sqr), which the unfused form silently turns into 0.
template <class A>
inline constexpr bool kHasFusedFma =
    std::is_base_of_v<xsimd::fma3<xsimd::sse4_2>, A> ||
    std::is_base_of_v<xsimd::fma3<xsimd::avx>, A> ||
    std::is_base_of_v<xsimd::fma3<xsimd::avx2>, A> || std::is_base_of_v<xsimd::avx512f, A>;
// The xsimd arch types are not one chain (fma3<avx2> derives from avx2, avx512f from generic).
static_assert(kHasFusedFma<xsimd::fma3<xsimd::avx2>> && kHasFusedFma<xsimd::avx512bw> &&
              !kHasFusedFma<xsimd::sse4_2>);

// --- Raw ops: one overload set per raw type, used only by the Wide ops below -------------------
namespace raw {

GLINTLAB_FN float select(bool m, float a, float b) { return m ? a : b; }
GLINTLAB_FN double select(bool m, double a, double b) { return m ? a : b; }
template <class S, class A>
GLINTLAB_FN xsimd::batch<S, A> select(const xsimd::batch_bool<S, A>& m, const xsimd::batch<S, A>& a,
                                      const xsimd::batch<S, A>& b) {
  return xsimd::select(m, a, b);
}

template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN S fma(S a, S b, S c) { return std::fma(a, b, c); }
// Fused multiply-add. Without FMA hardware (SSE4.2) it is emulated: float through double (the
// product of two floats is exact in double; one extra rounding, off by at most 1 ulp in rare
// ties), double by Dekker's error-free product (Dekker 1971) and a compensated sum, exact for the
// kernels' x·x − fl(x·x) and within 1 ulp otherwise.
template <class S, class A>
GLINTLAB_FN xsimd::batch<S, A> fma(const xsimd::batch<S, A>& a, const xsimd::batch<S, A>& b,
                                   const xsimd::batch<S, A>& c) {
  if constexpr (kHasFusedFma<A>) {
    return xsimd::fma(a, b, c);
  } else if constexpr (std::is_same_v<S, float>) {
    using D = xsimd::batch<double, A>;
    constexpr std::size_t kN = xsimd::batch<S, A>::size;
    alignas(64) float fa[kN], fb[kN], fc[kN];
    a.store_aligned(fa);
    b.store_aligned(fb);
    c.store_aligned(fc);
    alignas(64) double da[kN], db[kN], dc[kN];
    for (std::size_t i = 0; i < kN; ++i) {
      da[i] = fa[i];
      db[i] = fb[i];
      dc[i] = fc[i];
    }
    alignas(64) float r[kN];
    constexpr std::size_t kD = D::size;
    for (std::size_t i = 0; i < kN; i += kD) {
      const D p = D::load_aligned(da + i) * D::load_aligned(db + i) + D::load_aligned(dc + i);
      alignas(64) double pd[kD];
      p.store_aligned(pd);
      for (std::size_t j = 0; j < kD; ++j) r[i + j] = static_cast<float>(pd[j]);
    }
    return xsimd::batch<S, A>::load_aligned(r);
  } else {
    using Bt = xsimd::batch<S, A>;
    const Bt split(134217729.0);  // 2^27 + 1
    const auto two_split = [&](const Bt& x, Bt& hi, Bt& lo) {
      const Bt t = split * x;
      hi = t - (t - x);
      lo = x - hi;
    };
    Bt ah, al, bh, bl;
    two_split(a, ah, al);
    two_split(b, bh, bl);
    const Bt p = a * b;
    const Bt e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;  // a*b = p + e exactly
    const Bt s = p + c;
    const Bt bv = s - p;
    const Bt err = (p - (s - bv)) + (c - bv);  // p + c = s + err exactly (Knuth's TwoSum)
    return s + (err + e);
  }
}

// min/max with std::fmin/fmax's rule (a NaN operand yields the other one), so that lanes agree
// with the scalar kernels wherever a discarded branch produced a NaN.
template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN S min(S a, S b) { return std::fmin(a, b); }
template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN S max(S a, S b) { return std::fmax(a, b); }
// NaN is tested with isnan: xsimd 8.1's != is the ordered comparison on AVX and AVX-512 (NaN != NaN
// false there). Of two zeros of opposite signs the batch returns its first operand (the min/max
// instructions return their second, hence the swap), as GCC's inline fmin/fmax do at -O2; glibc's
// out-of-line fminf/fmaxf return the second, so the sign can differ from a libm call
// (docs/simd.md).
template <class S, class A>
GLINTLAB_FN xsimd::batch<S, A> min(const xsimd::batch<S, A>& a, const xsimd::batch<S, A>& b) {
  return xsimd::select(xsimd::isnan(b), a, xsimd::select(xsimd::isnan(a), b, xsimd::min(b, a)));
}
template <class S, class A>
GLINTLAB_FN xsimd::batch<S, A> max(const xsimd::batch<S, A>& a, const xsimd::batch<S, A>& b) {
  return xsimd::select(xsimd::isnan(b), a, xsimd::select(xsimd::isnan(a), b, xsimd::max(b, a)));
}

// The hardware reciprocal square-root estimate (12 bits on SSE/AVX, 14 on AVX-512).
GLINTLAB_FN float rsqrt_estimate(float x) {
#if defined(__SSE__)
  return _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
#else
  return 1.0f / std::sqrt(x);
#endif
}
template <class A>
GLINTLAB_FN xsimd::batch<float, A> rsqrt_estimate(const xsimd::batch<float, A>& x) {
#if defined(__AVX512F__)
  // xsimd 8.1's AVX-512 rsqrt calls _mm512_rsqrt23_ps, which GCC does not provide.
  if constexpr (std::is_base_of_v<xsimd::avx512f, A>) {
    return xsimd::batch<float, A>(_mm512_rsqrt14_ps(x));
  } else
#endif
  {
    return xsimd::rsqrt(x);
  }
}

// 2^n for a float holding an integer n in [−126, 127], by building the exponent field.
GLINTLAB_FN float pow2_int(float n) {
  return std::bit_cast<float>(static_cast<std::int32_t>(n + 127.0f) << 23);
}
template <class A>
GLINTLAB_FN xsimd::batch<float, A> pow2_int(const xsimd::batch<float, A>& n) {
  const auto bits = xsimd::to_int(n + xsimd::batch<float, A>(127.0f)) << 23;
  return xsimd::bitwise_cast<xsimd::batch<float, A>>(bits);
}
GLINTLAB_FN float round_nearest(float x) { return std::nearbyint(x); }
template <class A>
GLINTLAB_FN xsimd::batch<float, A> round_nearest(const xsimd::batch<float, A>& x) {
  return xsimd::nearbyint(x);
}

#define GLINTLAB_RAW_UNARY(name, stdname)                                                  \
  template <class S>                                                                       \
  requires std::is_floating_point_v<S> GLINTLAB_FN S name(S x) { return std::stdname(x); } \
  template <class S, class A>                                                              \
  GLINTLAB_FN xsimd::batch<S, A> name(const xsimd::batch<S, A>& x) {                       \
    return xsimd::name(x);                                                                 \
  }
GLINTLAB_RAW_UNARY(abs, fabs)
GLINTLAB_RAW_UNARY(sqrt, sqrt)
GLINTLAB_RAW_UNARY(floor, floor)
GLINTLAB_RAW_UNARY(exp, exp)
GLINTLAB_RAW_UNARY(expm1, expm1)
GLINTLAB_RAW_UNARY(log, log)
GLINTLAB_RAW_UNARY(log1p, log1p)
GLINTLAB_RAW_UNARY(erf, erf)
GLINTLAB_RAW_UNARY(erfc, erfc)
GLINTLAB_RAW_UNARY(sin, sin)
GLINTLAB_RAW_UNARY(cos, cos)
GLINTLAB_RAW_UNARY(tan, tan)
GLINTLAB_RAW_UNARY(atan, atan)
GLINTLAB_RAW_UNARY(acos, acos)
GLINTLAB_RAW_UNARY(acosh, acosh)
#undef GLINTLAB_RAW_UNARY

template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN S copysign(S a, S b) {
  return std::copysign(a, b);
}
template <class S, class A>
GLINTLAB_FN xsimd::batch<S, A> copysign(const xsimd::batch<S, A>& a, const xsimd::batch<S, A>& b) {
  return xsimd::copysign(a, b);
}
template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN S atan2(S y, S x) { return std::atan2(y, x); }
template <class S, class A>
GLINTLAB_FN xsimd::batch<S, A> atan2(const xsimd::batch<S, A>& y, const xsimd::batch<S, A>& x) {
  return xsimd::atan2(y, x);
}
template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN void sincos(S x, S* s, S* c) {
  *s = std::sin(x);
  *c = std::cos(x);
}
template <class S, class A>
GLINTLAB_FN void sincos(const xsimd::batch<S, A>& x, xsimd::batch<S, A>* s, xsimd::batch<S, A>* c) {
  const auto sc = xsimd::sincos(x);
  *s = sc.first;
  *c = sc.second;
}
template <class S>
requires std::is_floating_point_v<S> GLINTLAB_FN bool isfinite(S x) { return std::isfinite(x); }
template <class S, class A>
GLINTLAB_FN xsimd::batch_bool<S, A> isfinite(const xsimd::batch<S, A>& x) {
  return xsimd::isfinite(x);
}

}  // namespace raw

}  // namespace glintlab

#include "core/simd/fast_math.h"

namespace glintlab {

// Math policies. A policy may provide static exp, erf, erfc or rsqrt on the raw type; the Wide
// ops below use them in place of the exact ones (and ggx_d, which the ggx.d kernel uses).
// ExactMath: none, every op as accurate as the scalar ops layer (xsimd's vectorized libm, within a
// few ulp of glibc). FastMath: the shader-style approximations of core/simd/fast_math.h (errors
// measured there), float only.
struct ExactMath {};
struct FastMath {
  template <class B>
  static GLINTLAB_FN B exp(const B& x) {
    return fast::exp(x);
  }
  template <class B>
  static GLINTLAB_FN B erf(const B& x) {
    return fast::erf(x);
  }
  template <class B>
  static GLINTLAB_FN B erfc(const B& x) {
    return fast::erfc(x);
  }
  template <class B>
  static GLINTLAB_FN B rsqrt(const B& x) {
    return fast::rsqrt(x);
  }
  // Not an op of ops.h: the ggx.d kernel of core/simd/kernels.h calls it in place of GGX<T>::D.
  template <class B>
  static GLINTLAB_FN B ggx_d(const B& ax, const B& ay, const B& mx, const B& my, const B& mz) {
    return fast::ggx_d(ax, ay, mx, my, mz);
  }
};

// --- The wrapper ---------------------------------------------------------------------------------
template <class B, class M = ExactMath>
struct Wide {
  using Raw = B;
  using Policy = M;
  using ScalarType = typename RawTraits<B>::scalar;
  using MaskType = typename RawTraits<B>::mask;
  static constexpr std::size_t kLanes = RawTraits<B>::kLanes;

  B v;

  Wide() = default;
  // From a number: T(0.5), T(kPi<T>), T(2 * k − 1), as for a plain float (explicit, like the
  // functional casts the kernels write; the narrowing is deliberate there).
  template <class U>
  requires std::is_arithmetic_v<U>
  constexpr explicit Wide(U x) : v(static_cast<ScalarType>(x)) {}
  // From a raw register (a batch; for B = float the constructor above covers it).
  template <class R>
  requires(std::is_same_v<R, B> && !std::is_arithmetic_v<B>) constexpr explicit Wide(const R& x)
      : v(x) {}

  static GLINTLAB_FN Wide wrap(const B& x) {
    Wide w;
    w.v = x;
    return w;
  }

  friend GLINTLAB_FN Wide operator+(Wide a, Wide b) { return wrap(a.v + b.v); }
  friend GLINTLAB_FN Wide operator-(Wide a, Wide b) { return wrap(a.v - b.v); }
  friend GLINTLAB_FN Wide operator*(Wide a, Wide b) { return wrap(a.v * b.v); }
  friend GLINTLAB_FN Wide operator/(Wide a, Wide b) { return wrap(a.v / b.v); }
  friend GLINTLAB_FN Wide operator-(Wide a) { return wrap(-a.v); }
  GLINTLAB_FN Wide& operator+=(Wide b) { return *this = *this + b; }
  GLINTLAB_FN Wide& operator-=(Wide b) { return *this = *this - b; }
  GLINTLAB_FN Wide& operator*=(Wide b) { return *this = *this * b; }
  GLINTLAB_FN Wide& operator/=(Wide b) { return *this = *this / b; }
  friend GLINTLAB_FN MaskType operator<(Wide a, Wide b) { return a.v < b.v; }
  friend GLINTLAB_FN MaskType operator<=(Wide a, Wide b) { return a.v <= b.v; }
  friend GLINTLAB_FN MaskType operator>(Wide a, Wide b) { return a.v > b.v; }
  friend GLINTLAB_FN MaskType operator>=(Wide a, Wide b) { return a.v >= b.v; }
  friend GLINTLAB_FN MaskType operator==(Wide a, Wide b) { return a.v == b.v; }
  // Unordered, as the scalar a != b (true when either is NaN). Not the batch's own !=: xsimd 8.1's
  // AVX and AVX-512 kernels use the ordered comparison, its SSE kernels the unordered one.
  friend GLINTLAB_FN MaskType operator!=(Wide a, Wide b) { return !(a.v == b.v); }
};

template <class B, class M>
struct MaskOf<Wide<B, M>> {
  using type = typename Wide<B, M>::MaskType;
};
template <class B, class M>
struct ScalarOf<Wide<B, M>> {
  using type = typename Wide<B, M>::ScalarType;
};

// Lane access (core/math/lanes.h) of a Wide: through memory, for the per-lane integer code.
template <class B, class M>
struct LaneAccess<Wide<B, M>> {
  using W = Wide<B, M>;
  using S = typename W::ScalarType;
  static constexpr std::size_t kLanes = W::kLanes;
  static GLINTLAB_FN void store(const W& x, S* out) {
    if constexpr (std::is_floating_point_v<B>)
      out[0] = x.v;
    else
      x.v.store_unaligned(out);
  }
  static GLINTLAB_FN W load(const S* in) {
    if constexpr (std::is_floating_point_v<B>)
      return W(in[0]);
    else
      return W::wrap(B::load_unaligned(in));
  }
  static GLINTLAB_FN void store_mask(const typename W::MaskType& m, bool* out) {
    if constexpr (std::is_floating_point_v<B>)
      out[0] = m;
    else
      m.store_unaligned(out);
  }
  static GLINTLAB_FN typename W::MaskType load_mask(const bool* in) {
    if constexpr (std::is_floating_point_v<B>)
      return in[0];
    else
      return W::MaskType::load_unaligned(in);
  }
  static GLINTLAB_FN bool any(const typename W::MaskType& m) {
    if constexpr (std::is_floating_point_v<B>)
      return m;
    else
      return xsimd::any(m);
  }
};

template <class T>
inline constexpr bool kIsWide = false;
template <class B, class M>
inline constexpr bool kIsWide<Wide<B, M>> = true;

// --- Ops on Wide: found by ADL from any kernel, whatever the include order ----------------------
template <class B, class M>
GLINTLAB_FN Wide<B, M> select(const typename Wide<B, M>::MaskType& m, Wide<B, M> a, Wide<B, M> b) {
  return Wide<B, M>::wrap(raw::select(m, a.v, b.v));
}
template <class S, class A>
GLINTLAB_FN xsimd::batch_bool<S, A> select(const xsimd::batch_bool<S, A>& m,
                                           const xsimd::batch_bool<S, A>& a,
                                           const xsimd::batch_bool<S, A>& b) {
  return (m && a) || ((!m) && b);
}
template <class S, class A>
GLINTLAB_FN bool any(const xsimd::batch_bool<S, A>& m) {
  return xsimd::any(m);
}
template <class S, class A>
GLINTLAB_FN bool all(const xsimd::batch_bool<S, A>& m) {
  return xsimd::all(m);
}

template <class B, class M>
GLINTLAB_FN Wide<B, M> fma(Wide<B, M> a, Wide<B, M> b, Wide<B, M> c) {
  return Wide<B, M>::wrap(raw::fma(a.v, b.v, c.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> min(Wide<B, M> a, Wide<B, M> b) {
  return Wide<B, M>::wrap(raw::min(a.v, b.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> max(Wide<B, M> a, Wide<B, M> b) {
  return Wide<B, M>::wrap(raw::max(a.v, b.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> copysign(Wide<B, M> a, Wide<B, M> b) {
  return Wide<B, M>::wrap(raw::copysign(a.v, b.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> sign_not_zero(Wide<B, M> x) {
  return Wide<B, M>::wrap(raw::copysign(B(typename Wide<B, M>::ScalarType(1)), x.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> atan2(Wide<B, M> y, Wide<B, M> x) {
  return Wide<B, M>::wrap(raw::atan2(y.v, x.v));
}
template <class B, class M>
GLINTLAB_FN void sincos(Wide<B, M> x, Wide<B, M>* s, Wide<B, M>* c) {
  raw::sincos(x.v, &s->v, &c->v);
}
template <class B, class M>
GLINTLAB_FN typename Wide<B, M>::MaskType isfinite(Wide<B, M> x) {
  return raw::isfinite(x.v);
}

#define GLINTLAB_WIDE_UNARY(name)             \
  template <class B, class M>                 \
  GLINTLAB_FN Wide<B, M> name(Wide<B, M> x) { \
    return Wide<B, M>::wrap(raw::name(x.v));  \
  }
GLINTLAB_WIDE_UNARY(abs)
GLINTLAB_WIDE_UNARY(sqrt)
GLINTLAB_WIDE_UNARY(floor)
GLINTLAB_WIDE_UNARY(expm1)
GLINTLAB_WIDE_UNARY(log)
GLINTLAB_WIDE_UNARY(log1p)
GLINTLAB_WIDE_UNARY(sin)
GLINTLAB_WIDE_UNARY(cos)
GLINTLAB_WIDE_UNARY(tan)
GLINTLAB_WIDE_UNARY(atan)
GLINTLAB_WIDE_UNARY(acos)
GLINTLAB_WIDE_UNARY(acosh)
#undef GLINTLAB_WIDE_UNARY

// The ops a policy may replace (see ExactMath/FastMath above).
template <class B, class M>
GLINTLAB_FN Wide<B, M> exp(Wide<B, M> x) {
  if constexpr (requires { M::exp(x.v); })
    return Wide<B, M>::wrap(M::exp(x.v));
  else
    return Wide<B, M>::wrap(raw::exp(x.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> erf(Wide<B, M> x) {
  if constexpr (requires { M::erf(x.v); })
    return Wide<B, M>::wrap(M::erf(x.v));
  else
    return Wide<B, M>::wrap(raw::erf(x.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> erfc(Wide<B, M> x) {
  if constexpr (requires { M::erfc(x.v); })
    return Wide<B, M>::wrap(M::erfc(x.v));
  else
    return Wide<B, M>::wrap(raw::erfc(x.v));
}
template <class B, class M>
GLINTLAB_FN Wide<B, M> rsqrt(Wide<B, M> x) {
  using S = typename Wide<B, M>::ScalarType;
  if constexpr (requires { M::rsqrt(x.v); })
    return Wide<B, M>::wrap(M::rsqrt(x.v));
  else
    return Wide<B, M>::wrap(B(S(1)) / raw::sqrt(x.v));
}

}  // namespace glintlab

#include "core/simd/wide_lanes.h"  // per-lane access for the counter RNG and gathers
