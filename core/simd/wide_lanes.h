// LaneTraits (core/math/lane_rng.h) for Wide<B, M>: lane stores and loads of the SIMD batches, and
// the double batch of the same ISA for the kernels' double-precision steps (the exact binomial).
#pragma once

#include <type_traits>

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

}  // namespace glintlab
