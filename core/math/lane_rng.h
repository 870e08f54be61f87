// Per-lane access to a kernel's float type (one lane for float/double; core/simd/wide_lanes.h
// specializes it for the SIMD batches): the counter RNG keyed per lane (core/math/rng.h), table
// gathers and the double type of the same width (any_lane is core/math/lanes.h's), so kernels
// that need a per-lane 64-bit counter or an exact double-precision step instantiate on batches
// with every lane's scalar result.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "core/math/config.h"
#include "core/math/lanes.h"
#include "core/math/rng.h"

namespace glintlab {

// Lane access of T: kLanes values of Scalar<T>, stored to and loaded from plain arrays. The
// primary template is the one-lane case of float and double.
template <class T>
struct LaneTraits {
  static constexpr std::size_t kLanes = 1;
  // The double type with the same lanes split into kLanes / Double::kLanes parts (double itself
  // for scalars: one part).
  using Double = double;
  static GLINTLAB_FN void store(const T& x, Scalar<T>* out) { out[0] = x; }
  static GLINTLAB_FN T load(const Scalar<T>* in) { return in[0]; }
  // Whether any lane of a mask is set (the exit test of a masked loop).
  static GLINTLAB_FN bool any(const Mask<T>& m) { return m; }
};

template <class T>
inline constexpr std::size_t kLanesOfType = LaneTraits<T>::kLanes;

// The counter-RNG index of each lane (core/math/rng.h): a plain std::uint64_t for scalars (the
// interface the scalar kernels always had), one per lane for a batch.
template <class T>
using RngIndex = std::conditional_t<std::is_floating_point_v<T>, std::uint64_t,
                                    std::array<std::uint64_t, LaneTraits<T>::kLanes>>;

// Index l of an RngIndex (l = 0 for a scalar).
template <class T>
GLINTLAB_FN std::uint64_t rng_lane(const RngIndex<T>& index, std::size_t l) {
  if constexpr (std::is_floating_point_v<T>) {
    (void)l;
    return index;
  } else {
    return index[l];
  }
}

// counter_uniform<Scalar<T>>(seed, index of lane l, dim) in every lane l: each lane the very
// number the scalar kernel draws for its index (the dimension is uniform over the batch).
template <class T>
GLINTLAB_FN T lane_uniform(std::uint64_t seed, const RngIndex<T>& index, std::uint64_t dim) {
  if constexpr (std::is_floating_point_v<T>) {
    return counter_uniform<T>(seed, index, dim);
  } else {
    constexpr std::size_t kL = LaneTraits<T>::kLanes;
    alignas(64) Scalar<T> v[kL];
    for (std::size_t l = 0; l < kL; ++l) v[l] = counter_uniform<Scalar<T>>(seed, index[l], dim);
    return LaneTraits<T>::load(v);
  }
}

// table[i] in every lane for i = the lane's value of `at`, an integer in [0, size) (the caller
// clamps): a gather.
template <class T>
GLINTLAB_FN T lane_gather(const Scalar<T>* table, T at) {
  constexpr std::size_t kL = LaneTraits<T>::kLanes;
  alignas(64) Scalar<T> v[kL];
  LaneTraits<T>::store(at, v);
  for (std::size_t l = 0; l < kL; ++l) v[l] = table[static_cast<std::size_t>(v[l])];
  return LaneTraits<T>::load(v);
}

}  // namespace glintlab
