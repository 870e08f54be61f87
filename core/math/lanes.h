// Per-lane integers for kernels written on a float type T: the integer of each lane (a cell index,
// a MIP level, a hash) next to T, plain integers for scalar T and lane arrays for SIMD batches.
#pragma once

// Why: the glint kernels (Kemppinen et al. 2025 Algorithm 1–2) index an implicit grid by integer
// cell coordinates and hash them (core/glints/kemppinen_grid.h). On a batch each lane has its
// own cells, so the integers are lane arrays, computed lane by lane with the scalar integer code
// (bit-identical to the scalar kernel by construction; loops over the uniform lane count, no
// per-lane branches). A batch backend (core/simd/wide.h) specializes LaneAccess.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "core/math/config.h"
#include "core/math/ops.h"

namespace glintlab {

// Lane access of a float type: store/load its lanes and those of its mask. Scalars: one lane.
template <class T>
struct LaneAccess {
  static constexpr std::size_t kLanes = 1;
  static GLINTLAB_FN void store(T x, Scalar<T>* out) { out[0] = x; }
  static GLINTLAB_FN T load(const Scalar<T>* in) { return in[0]; }
  static GLINTLAB_FN void store_mask(Mask<T> m, bool* out) { out[0] = m; }
  static GLINTLAB_FN Mask<T> load_mask(const bool* in) { return in[0]; }
  static GLINTLAB_FN bool any(Mask<T> m) { return m; }
};
template <class T>
inline constexpr std::size_t kLaneCount = LaneAccess<T>::kLanes;

// Whether any lane of the mask is set: for uniform early-outs (all lanes done), never to branch
// on one lane's value.
template <class T>
GLINTLAB_FN bool any_lane(const Mask<T>& m) {
  return LaneAccess<T>::any(m);
}

// N integers, one per lane of a batch.
template <class I, std::size_t N>
struct IntLanes {
  I v[N];
};

// The integer type I per lane of T: I itself for float/double, IntLanes for batches.
template <class T, class I = std::int64_t>
using LaneInt = std::conditional_t<std::is_floating_point_v<T>, I, IntLanes<I, kLaneCount<T>>>;

// Lane l of an integer (a plain integer is the same in every lane).
template <class I>
requires std::is_integral_v<I> GLINTLAB_FN I lane(I x, std::size_t) { return x; }
template <class I, std::size_t N>
GLINTLAB_FN I lane(const IntLanes<I, N>& x, std::size_t l) {
  return x.v[l];
}

// f(l) for every lane l, as integers, floats or a mask of T.
template <class T, class I = std::int64_t, class F>
GLINTLAB_FN LaneInt<T, I> int_lanes(F f) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<I>(f(std::size_t(0)));
  } else {
    LaneInt<T, I> r;
    for (std::size_t l = 0; l < kLaneCount<T>; ++l) r.v[l] = static_cast<I>(f(l));
    return r;
  }
}
template <class T, class F>
GLINTLAB_FN T float_lanes(F f) {
  if constexpr (std::is_floating_point_v<T>) {
    return f(std::size_t(0));
  } else {
    Scalar<T> s[kLaneCount<T>];
    for (std::size_t l = 0; l < kLaneCount<T>; ++l) s[l] = f(l);
    return LaneAccess<T>::load(s);
  }
}
template <class T, class F>
GLINTLAB_FN Mask<T> mask_lanes(F f) {
  if constexpr (std::is_floating_point_v<T>) {
    return f(std::size_t(0));
  } else {
    bool b[kLaneCount<T>];
    for (std::size_t l = 0; l < kLaneCount<T>; ++l) b[l] = f(l);
    return LaneAccess<T>::load_mask(b);
  }
}

// The scalar lanes of x (x itself for scalar T), for float_lanes/int_lanes bodies.
template <class T>
struct LanesOf {
  Scalar<T> s[kLaneCount<T>];
  GLINTLAB_FN explicit LanesOf(const T& x) { LaneAccess<T>::store(x, s); }
  GLINTLAB_FN Scalar<T> operator[](std::size_t l) const { return s[l]; }
};
template <class T>
struct MaskLanesOf {
  bool b[kLaneCount<T>];
  GLINTLAB_FN explicit MaskLanesOf(const Mask<T>& m) { LaneAccess<T>::store_mask(m, b); }
  GLINTLAB_FN bool operator[](std::size_t l) const { return b[l]; }
};

// floor(x) as an integer per lane. Non-finite lanes give 0 and magnitudes are clamped to 2^52
// (the float→integer conversion of those is undefined; a discarded SIMD lane may hold them).
template <class T, class I = std::int64_t>
GLINTLAB_FN LaneInt<T, I> floor_int(T x) {
  const LanesOf<T> f(floor(x));
  return int_lanes<T, I>([&](std::size_t l) {
    const Scalar<T> v = f[l];
    const Scalar<T> big = Scalar<T>(4503599627370496.0);  // 2^52
    return std::isfinite(v) ? static_cast<I>(v < -big ? -big : (v > big ? big : v)) : I(0);
  });
}

// The integer of each lane as T.
template <class T, class L>
GLINTLAB_FN T int_to_float(const L& x) {
  return float_lanes<T>([&](std::size_t l) { return static_cast<Scalar<T>>(lane(x, l)); });
}

// Lane-wise integer arithmetic, min/max and select.
template <class I, std::size_t N, class J>
requires std::is_integral_v<J> GLINTLAB_FN IntLanes<I, N>
operator+(IntLanes<I, N> a, J b) {
  for (std::size_t l = 0; l < N; ++l) a.v[l] = static_cast<I>(a.v[l] + static_cast<I>(b));
  return a;
}
template <class I, std::size_t N, class J>
requires std::is_integral_v<J> GLINTLAB_FN IntLanes<I, N>
operator-(IntLanes<I, N> a, J b) {
  for (std::size_t l = 0; l < N; ++l) a.v[l] = static_cast<I>(a.v[l] - static_cast<I>(b));
  return a;
}
template <class I, std::size_t N>
GLINTLAB_FN IntLanes<I, N> operator+(IntLanes<I, N> a, const IntLanes<I, N>& b) {
  for (std::size_t l = 0; l < N; ++l) a.v[l] = static_cast<I>(a.v[l] + b.v[l]);
  return a;
}
template <class I>
requires std::is_integral_v<I> GLINTLAB_FN I int_min(I a, I b) { return a < b ? a : b; }
template <class I>
requires std::is_integral_v<I> GLINTLAB_FN I int_max(I a, I b) { return a < b ? b : a; }
template <class I, std::size_t N>
GLINTLAB_FN IntLanes<I, N> int_min(IntLanes<I, N> a, const IntLanes<I, N>& b) {
  for (std::size_t l = 0; l < N; ++l) a.v[l] = a.v[l] < b.v[l] ? a.v[l] : b.v[l];
  return a;
}
template <class I, std::size_t N>
GLINTLAB_FN IntLanes<I, N> int_max(IntLanes<I, N> a, const IntLanes<I, N>& b) {
  for (std::size_t l = 0; l < N; ++l) a.v[l] = a.v[l] < b.v[l] ? b.v[l] : a.v[l];
  return a;
}
template <class I, std::size_t N>
GLINTLAB_FN IntLanes<I, N> int_max(IntLanes<I, N> a, I b) {
  for (std::size_t l = 0; l < N; ++l) a.v[l] = a.v[l] < b ? b : a.v[l];
  return a;
}
template <class T, class L>
GLINTLAB_FN L int_select(const Mask<T>& m, const L& a, const L& b) {
  if constexpr (std::is_integral_v<L>) {
    return m ? a : b;
  } else {
    const MaskLanesOf<T> ml(m);
    L r;
    for (std::size_t l = 0; l < kLaneCount<T>; ++l) r.v[l] = ml[l] ? a.v[l] : b.v[l];
    return r;
  }
}

// 1 where the mask is set, else 0, per lane.
template <class T>
GLINTLAB_FN LaneInt<T, int> mask_to_int(const Mask<T>& m) {
  const MaskLanesOf<T> ml(m);
  return int_lanes<T, int>([&](std::size_t l) { return ml[l] ? 1 : 0; });
}

}  // namespace glintlab
