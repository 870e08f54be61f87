// LaneTraits (core/math/lane_rng.h) for Wide<B, M>: lane stores and loads of the SIMD batches, and
// the double batch of the same ISA for the kernels' double-precision steps (the exact binomial).
// HashLaneTraits (core/math/hash32.h): the integer lanes of a batch that hold its 32-bit hashes.
#pragma once

#include <cstdint>
#include <type_traits>

#include "core/math/hash32.h"
#include "core/math/lane_rng.h"
#include "core/simd/wide.h"
#include "core/simd/xsimd.h"

namespace glintlab {

template <class B, class M>
struct LaneTraits<Wide<B, M>> {
  using W = Wide<B, M>;
  static constexpr std::size_t kLanes = W::kLanes;
  using Double = double;  // Wide<float, M>: one lane
  static GLINTLAB_FN void store(const W& x, typename W::ScalarType* out) { out[0] = x.v; }
  static GLINTLAB_FN W load(const typename W::ScalarType* in) { return W(in[0]); }
  static GLINTLAB_FN bool any(bool m) { return m; }
};

template <class S, class A, class M>
struct LaneTraits<Wide<xsimd::batch<S, A>, M>> {
  using W = Wide<xsimd::batch<S, A>, M>;
  static constexpr std::size_t kLanes = W::kLanes;
  // Exact math: the double steps are the exact ones whatever the float policy.
  using Double = Wide<xsimd::batch<double, A>, ExactMath>;
  static GLINTLAB_FN void store(const W& x, S* out) { x.v.store_unaligned(out); }
  static GLINTLAB_FN W load(const S* in) { return W::wrap(xsimd::batch<S, A>::load_unaligned(in)); }
  static GLINTLAB_FN bool any(const xsimd::batch_bool<S, A>& m) { return xsimd::any(m); }
};

// One lane (Wide<float, M>, Wide<double, M>): the scalar hash lanes.
template <class B, class M>
requires std::is_floating_point_v<B>
struct HashLaneTraits<Wide<B, M>> {
  using W = Wide<B, M>;
  using U = std::uint32_t;
  static GLINTLAB_FN U from_index(const W& x) { return HashLaneTraits<B>::from_index(x.v); }
  static GLINTLAB_FN W to_uniform(U h) { return W::wrap(HashLaneTraits<B>::to_uniform(h)); }
};

// A batch: 32-bit lanes for float (the same count), 64-bit lanes holding 32-bit values for
// double. The conversions are exact (integers below 2^24 to float, below 2^32 to double), and the
// truncation is the scalar cast's, so every lane has the scalar bits.
template <class S, class A, class M>
struct HashLaneTraits<Wide<xsimd::batch<S, A>, M>> {
  using W = Wide<xsimd::batch<S, A>, M>;
  using B = xsimd::batch<S, A>;
  using I = std::conditional_t<sizeof(S) == 4, std::int32_t, std::int64_t>;
  using U = xsimd::batch<std::make_unsigned_t<I>, A>;
  static GLINTLAB_FN U from_index(const W& x) {
    const auto in_range = (x.v > B(S(-2147483648.0))) & (x.v < B(S(2147483648.0)));
    const auto i = xsimd::batch_cast<I>(xsimd::select(in_range, x.v, B(S(0))));
    return detail::wrap32(xsimd::bitwise_cast<U>(i));
  }
  static GLINTLAB_FN W to_uniform(const U& h) {
    if constexpr (sizeof(S) == 4)
      return W::wrap(xsimd::batch_cast<S>(xsimd::bitwise_cast<xsimd::batch<I, A>>(h >> 8)) *
                     B(S(1.0 / 16777216.0)));
    else
      return W::wrap(xsimd::batch_cast<S>(xsimd::bitwise_cast<xsimd::batch<I, A>>(h)) *
                     B(S(1.0 / 4294967296.0)));
  }
};

}  // namespace glintlab
