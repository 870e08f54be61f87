// The Kemppinen grid's hashing on a batch's 64-bit lanes in vector registers: the last step of a
// cell's index chain (kemppinen_grid.h) and its uniforms (cell_uniform), the same bits as the
// scalar code lane by lane, with the work the uniforms of one cell share done once per cell.
//
// cell_uniform(seed, ci, dim) is counter_uniform(seed, ci, dim) (core/math/rng.h): three SplitMix64
// mixes, mix64(mix64(mix64(seed + K₁) ^ (ci + K₂)) ^ (dim·K₃ + K₄)), of which the first depends on
// the seed only and the second on the cell only. Here the first is computed once per call
// (cell_seed_key), the second once per cell (cell_key), and each uniform costs the third alone
// (key_uniform): 7 mixes for a point's 6 uniforms instead of 18. On a batch the mixes run on GCC
// vector types of the lane count (AVX-512DQ vpmullq, AVX2 and SSE4.2 the 32-bit multiplies GCC
// composes), which GCC 12 otherwise leaves lane by lane in some of these loops on AVX-512.
// tests/core/glints/kemppinen_shared_work_test.cpp pins every function to rng.h's and
// kemppinen_grid.h's, bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/glints/kemppinen_grid.h"
#include "core/math/lanes.h"
#include "core/math/rng.h"

namespace glintlab::kemppinen2025 {

// counter_bits's constants (core/math/rng.h).
inline constexpr std::uint64_t kCounterSeedAdd = 0x9e3779b97f4a7c15ULL;
inline constexpr std::uint64_t kCounterIndexAdd = 0x632be59bd9b4e019ULL;
inline constexpr std::uint64_t kCounterDimMul = 0xd1b54a32d192ed03ULL;
inline constexpr std::uint64_t kCounterDimAdd = 0x8cb92ba72f3d8dd7ULL;
// cell_chain_ax's and cell_chain_ay's multipliers (kemppinen_grid.h).
inline constexpr std::uint64_t kChainAxMul = 0x8cb92ba72f3d8dd7ULL;
inline constexpr std::uint64_t kChainAyMul = 0xabc98388fb8fac03ULL;

// The seed's step of counter_bits, the same for every cell of a call.
GLINTLAB_INLINE std::uint64_t cell_seed_key(std::uint64_t seed) {
  return mix64(seed + kCounterSeedAdd);
}

// N 64-bit lanes as one GCC vector (N > 1 only: a batch's lanes).
template <std::size_t N>
struct HashVector {
  typedef std::uint64_t type __attribute__((vector_size(8 * N)));
  typedef std::int32_t int32 __attribute__((vector_size(4 * N)));
  typedef float float32 __attribute__((vector_size(4 * N)));
  typedef std::int64_t int64 __attribute__((vector_size(8 * N)));
  typedef double float64 __attribute__((vector_size(8 * N)));
};

// mix64 of every lane, in place (by reference: a vector argument by value changes the ABI note
// GCC prints for wide vectors).
template <class V>
GLINTLAB_INLINE void mix64_vector(V& z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z = z ^ (z >> 31);
}

// The cell's step of counter_bits: mix64(seed_key ^ (ci + K₂)) per lane.
template <class T>
GLINTLAB_INLINE LaneInt<T, std::uint64_t> cell_key(std::uint64_t seed_key,
                                                   const LaneInt<T, std::uint64_t>& ci) {
  if constexpr (std::is_floating_point_v<T>) {
    return mix64(seed_key ^ (ci + kCounterIndexAdd));
  } else {
    using V = typename HashVector<kLaneCount<T>>::type;
    V v;
    std::memcpy(&v, ci.v, sizeof v);
    v = seed_key ^ (v + kCounterIndexAdd);
    mix64_vector(v);
    LaneInt<T, std::uint64_t> out;
    std::memcpy(out.v, &v, sizeof v);
    return out;
  }
}

// counter_uniform(seed, ci, dim) of every lane, from its cell key cell_key(cell_seed_key(seed), ci).
template <class T>
GLINTLAB_INLINE T key_uniform(const LaneInt<T, std::uint64_t>& key, std::uint64_t dim) {
  using S = Scalar<T>;
  constexpr int kBits = sizeof(S) == 4 ? 24 : 53;
  const std::uint64_t dim_key = dim * kCounterDimMul + kCounterDimAdd;
  if constexpr (std::is_floating_point_v<T>) {
    std::uint64_t z = key ^ dim_key;
    z = mix64(z) >> (64 - kBits);
    return T(z) * (T(1) / T(std::uint64_t(1) << kBits));
  } else {
    constexpr std::size_t kN = kLaneCount<T>;
    using H = HashVector<kN>;
    typename H::type v;
    std::memcpy(&v, key.v, sizeof v);
    v ^= dim_key;
    mix64_vector(v);
    v >>= (64 - kBits);
    // Below 2^24 (float) or 2^53 (double): exact through the signed conversions, as T(b) is.
    constexpr S kScale = S(1) / S(std::uint64_t(1) << kBits);
    S s[kN];
    if constexpr (sizeof(S) == 4) {
      const typename H::float32 f =
          __builtin_convertvector(__builtin_convertvector(v, typename H::int32), typename H::float32);
      const typename H::float32 u = f * kScale;
      std::memcpy(s, &u, sizeof s);
    } else {
      const typename H::float64 f =
          __builtin_convertvector(__builtin_convertvector(v, typename H::int64), typename H::float64);
      const typename H::float64 u = f * kScale;
      std::memcpy(s, &u, sizeof s);
    }
    return LaneAccess<T>::load(s);
  }
}

// cell_chain_ax_lanes(h, ax) (kemppinen_grid.h): the ax step of the chain per lane.
template <class T>
GLINTLAB_INLINE LaneInt<T, std::uint64_t> cell_chain_ax_vector(const LaneInt<T, std::uint64_t>& h,
                                                               const LaneInt<T>& ax) {
  if constexpr (std::is_floating_point_v<T>) {
    return cell_chain_ax(h, ax);
  } else {
    using V = typename HashVector<kLaneCount<T>>::type;
    V v, a;
    std::memcpy(&v, h.v, sizeof v);
    std::memcpy(&a, ax.v, sizeof a);  // int64 lanes: static_cast<uint64_t> keeps the bits
    v = v ^ (a * kChainAxMul);
    mix64_vector(v);
    LaneInt<T, std::uint64_t> out;
    std::memcpy(out.v, &v, sizeof v);
    return out;
  }
}

// cell_chain_ay_level_lanes(h, ay, level, process) (kemppinen_grid.h): the ay and level steps of
// the chain per lane.
template <class T>
GLINTLAB_INLINE LaneInt<T, std::uint64_t> cell_chain_ay_level_vector(
    const LaneInt<T, std::uint64_t>& h, const LaneInt<T>& ay, const LaneInt<T, int>& level,
    int process) {
  if constexpr (std::is_floating_point_v<T>) {
    return cell_chain_level(cell_chain_ay(h, ay), level, process);
  } else {
    constexpr std::size_t kN = kLaneCount<T>;
    using H = HashVector<kN>;
    typename H::type v, a, lv;
    std::memcpy(&v, h.v, sizeof v);
    std::memcpy(&a, ay.v, sizeof a);  // int64 lanes: static_cast<uint64_t> keeps the bits
    typename H::int32 level32;
    std::memcpy(&level32, level.v, sizeof level32);
    lv = __builtin_convertvector(level32, typename H::type);  // static_cast<uint64_t>(int)
    v = v ^ (a * kChainAyMul);
    mix64_vector(v);
    v = v ^ (lv << 8) ^ static_cast<std::uint64_t>(process);
    mix64_vector(v);
    LaneInt<T, std::uint64_t> out;
    std::memcpy(out.v, &v, sizeof v);
    return out;
  }
}

}  // namespace glintlab::kemppinen2025
