// A 32-bit counter-based hash computed on every lane at once, the kind GPU shaders use (Jarzynski
// & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3): a few 32-bit multiplies and
// xor-shifts, no tables, no 64-bit arithmetic). The mixer is Wellons' "lowbias32" (2018, the
// hash-prospector search: xor-shift 16, multiply, xor-shift 15, multiply, xor-shift 16), a
// bijection of the 32-bit integers. Unlike core/math/rng.h's 64-bit SplitMix counters, which a
// batch computes lane by lane through memory, these run on the batch's own integer lanes
// (core/simd/wide_lanes.h specializes HashLaneTraits): float batches hash in 32-bit lanes of the
// same count, double batches in 64-bit lanes holding 32-bit values. Every lane gives the bits the
// scalar code gives (tests/simd/avx512_ops_test.cpp); the uniformity and avalanche of the mixer
// are tested with weak hashes as negative controls (tests/core/math/hash32_test.cpp).
#pragma once

#include <cstdint>
#include <type_traits>

#include "core/math/config.h"
#include "core/math/ops.h"

namespace glintlab {

// The unsigned lanes that hold 32-bit hashes for the float type T, conversions from T's lanes
// (integral values: cell coordinates, levels) and to uniforms of T. The primary template is the
// scalar case (float, double).
template <class T>
struct HashLaneTraits {
  using U = std::uint32_t;
  // The lane's value truncated to an integer, as its 32-bit two's complement; lanes outside
  // (−2^31, 2^31) and NaN give 0 (every ISA alike).
  static GLINTLAB_FN U from_index(T x) {
    const bool in_range = x > T(-2147483648.0) && x < T(2147483648.0);
    return in_range ? static_cast<U>(static_cast<std::int32_t>(x)) : U(0);
  }
  // Uniform in [0, 1): the top 24 bits for float, all 32 for double (exact in either).
  static GLINTLAB_FN T to_uniform(U h) {
    if constexpr (sizeof(T) == 4)
      return static_cast<T>(h >> 8) * T(1.0 / 16777216.0);
    else
      return static_cast<T>(h) * T(1.0 / 4294967296.0);
  }
};

template <class T>
using HashLanes = typename HashLaneTraits<T>::U;

namespace detail {
// x mod 2^32, for lane types wider than 32 bits (a double batch's 64-bit lanes).
template <class U>
[[gnu::always_inline]] GLINTLAB_FN U wrap32(const U& x) {
  if constexpr (std::is_integral_v<U>) {
    if constexpr (sizeof(U) == 4)
      return x;
    else
      return x & U(0xffffffffu);
  } else if constexpr (sizeof(typename U::value_type) == 4) {
    return x;
  } else {
    return x & U(0xffffffffu);
  }
}
}  // namespace detail

// lowbias32: a bijection of the 32-bit integers whose output bits each flip with probability
// close to 1/2 when any input bit flips. hash32(0) = 0: key it through hash32_counter.
template <class U>
[[gnu::always_inline]] GLINTLAB_FN U hash32(U x) {
  x = x ^ (x >> 16);
  x = detail::wrap32(x * U(0x7feb352du));
  x = x ^ (x >> 15);
  x = detail::wrap32(x * U(0x846ca68bu));
  return x ^ (x >> 16);
}

// 32 random bits for (seed, index, dim), each counter mixed in turn (nested hashing, Jarzynski &
// Olano Sec. 2), offset so that all-zero counters do not hit hash32's fixed point.
template <class U>
[[gnu::always_inline]] GLINTLAB_FN U hash32_counter(const U& seed, const U& index, const U& dim) {
  U h = hash32(detail::wrap32(seed + U(0x9e3779b9u)));
  h = hash32(h ^ index);
  return hash32(h ^ detail::wrap32(dim * U(0x85ebca6bu) + U(0xc2b2ae35u)));
}

// A uniform of T in [0, 1) in every lane from its hash.
template <class T>
[[gnu::always_inline]] GLINTLAB_FN T hash32_uniform(const HashLanes<T>& h) {
  return HashLaneTraits<T>::to_uniform(h);
}

// The hash lanes of T's integral lanes (HashLaneTraits::from_index).
template <class T>
[[gnu::always_inline]] GLINTLAB_FN HashLanes<T> hash32_index(const T& x) {
  return HashLaneTraits<T>::from_index(x);
}

}  // namespace glintlab
