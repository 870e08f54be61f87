// The built-in models: one type list, the only place a model is added. core/model_registry.cpp
// makes a registry entry of each, in this order; the SIMD tables (core/simd/instantiate.h)
// instantiate each batched one on every ISA.
#pragma once

#include <cstddef>
#include <type_traits>

#include "core/glints/chermain.h"
#include "core/glints/deliot_belcour.h"
#include "core/glints/kneiphof.h"
#include "core/glints/kneiphof_ltc.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "core/models/podee.h"
#include "core/models/smooth_beckmann.h"
#include "core/models/smooth_ggx.h"

namespace glintlab {

template <class... Ms>
struct ModelList {
  static constexpr std::size_t kSize = sizeof...(Ms);
};

// Registration order is the order of `glintlab models` and of everything that iterates the
// registry.
using BuiltinModels = ModelList<SmoothGGX, SmoothBeckmann, Podee, DeliotBelcour, KneiphofKlein,
                                KneiphofKleinArea, Chermain, KemppinenGGX, KemppinenBeckmann>;

// A model runs on SIMD batches unless it declares `static constexpr bool kBatched = false;`
// (kernels that cannot instantiate on Wide<>, e.g. a scalar table lookup); the batch API then
// loops over its double thunks instead.
template <class M>
concept Batched = !requires {
  requires !M::kBatched;
};

namespace detail {
template <class... A, class... B>
constexpr ModelList<A..., B...> operator+(ModelList<A...>, ModelList<B...>) {
  return {};
}
template <class... Ms>
constexpr auto batched_of(ModelList<Ms...>) {
  return (ModelList<>{} + ... + std::conditional_t<Batched<Ms>, ModelList<Ms>, ModelList<>>{});
}
}  // namespace detail

// The models of BuiltinModels with SIMD instantiations, in registration order: the per-ISA tables
// hold their eval and sample (core/simd/table.h).
using BatchedModels = decltype(detail::batched_of(BuiltinModels{}));

}  // namespace glintlab
