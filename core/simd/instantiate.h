// The batch drivers and the table of one ISA: load SoA columns into one float type W, run a kernel
// functor or a model's own eval/sample template (core/model.h), store. Each ISA translation unit
// includes this once and builds its table with make_isa_table or make_xsimd_table (include in .cpp
// only).
#pragma once

#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>

// xsimd 8.1 has two non-template inline functions (the double-precision sin/cos argument
// reduction) whose out-of-line copies every ISA TU emits under one mangled name; the linker keeps
// one of them, possibly the AVX-512 one, for all ISAs. Renamed per TU, each ISA keeps its own
// (tests/simd/isa_symbols_test.cmake checks that no ISA object exports a shared weak symbol).
#if !defined(GLINTLAB_SIMD_TU)
#error "define GLINTLAB_SIMD_TU (a per-ISA token) before including core/simd/instantiate.h"
#endif
#define GLINTLAB_SIMD_CAT2(a, b) a##b
#define GLINTLAB_SIMD_CAT(a, b) GLINTLAB_SIMD_CAT2(a, b)
#define __ieee754_rem_pio2 GLINTLAB_SIMD_CAT(glintlab_ieee754_rem_pio2_, GLINTLAB_SIMD_TU)
#define __kernel_rem_pio2 GLINTLAB_SIMD_CAT(glintlab_kernel_rem_pio2_, GLINTLAB_SIMD_TU)
#include "core/simd/xsimd.h"
#undef __ieee754_rem_pio2
#undef __kernel_rem_pio2

#include "core/model_list.h"
#include "core/simd/kernels.h"
#include "core/simd/lane_params.h"
#include "core/simd/model_batch.h"
#include "core/simd/table.h"
#include "core/simd/wide.h"  // (any order works: the Wide ops are found by ADL, see wide.h)

namespace glintlab::simd::detail {
namespace {  // internal linkage: nothing here may be merged with another ISA's copy

template <class W>
constexpr std::size_t kLanesOf = 1;
template <class B, class M>
constexpr std::size_t kLanesOf<Wide<B, M>> = Wide<B, M>::kLanes;

template <class W, class S>
GLINTLAB_FN W load_lanes(const S* p) {
  if constexpr (std::is_floating_point_v<W>) {
    return *p;
  } else if constexpr (std::is_floating_point_v<typename W::Raw>) {
    return W(*p);
  } else {
    return W::wrap(W::Raw::load_unaligned(p));
  }
}

template <class W, class S>
GLINTLAB_FN void store_lanes(S* p, const W& w) {
  if constexpr (std::is_floating_point_v<W>) {
    *p = static_cast<S>(w);  // (a double-only model's double result into a float column)
  } else if constexpr (std::is_floating_point_v<typename W::Raw>) {
    *p = static_cast<S>(w.v);
  } else {
    w.v.store_unaligned(p);
  }
}

// Rows [i, i + count) of a column as one W; a partial batch is padded with row i (valid input,
// so the padding lanes compute something finite that is then dropped).
template <class W, class S>
GLINTLAB_FN W load_column(const Column<S>& c, std::size_t i, std::size_t count) {
  constexpr std::size_t kL = kLanesOf<W>;
  if (c.stride == 0) return W(c.data[0]);
  if (count == kL) return load_lanes<W>(c.data + i);
  alignas(64) S tmp[kL];
  for (std::size_t k = 0; k < kL; ++k) tmp[k] = c.data[i + (k < count ? k : 0)];
  return load_lanes<W>(tmp);
}

// The full batches of run_kernel. Every column is read at data + (i & mask): mask ~0 for a
// column of n values, 0 for a uniform one (data then points at kL copies of its value), so the
// loop has no per-column branch. The column and output loops are unrolled at compile time (the
// index packs), so x[] and y[] stay in registers: a runtime loop over the columns made GCC keep
// them on the stack, one store and reload per column and batch (docs/simd.md "Speed-ups": 37 % of
// ggx.d's AVX2 time). Only loads and stores differ from the tail's path; the kernel is the same
// instantiation, so every row's value is unchanged (bit for bit).
template <class K, class W, class S, std::size_t... J, std::size_t... O>
GLINTLAB_FN void run_full_batches(const S* const* base, const std::size_t* mask, S* const* outputs,
                                  std::size_t full, std::index_sequence<J...>,
                                  std::index_sequence<O...>) {
  constexpr std::size_t kL = kLanesOf<W>;
  for (std::size_t i = 0; i < full; i += kL) {
    const W x[] = {load_lanes<W>(base[J] + (i & mask[J]))...};
    W y[sizeof...(O)];
    K::template eval<W>(x, y);
    (store_lanes(outputs[O] + i, y[O]), ...);
  }
}

template <class K, class W, class S>
void run_kernel(const double* /*params*/, const Column<S>* inputs, S* const* outputs,
                std::size_t n) {
  constexpr std::size_t kL = kLanesOf<W>;
  constexpr std::size_t kIn = K::kIn.size();
  constexpr std::size_t kOut = K::kOut.size();
  // Full batches first, without the tail's per-batch count tests.
  alignas(64) S uniform[kIn][kL];
  const S* base[kIn];
  std::size_t mask[kIn];
  for (std::size_t j = 0; j < kIn; ++j) {
    if (inputs[j].stride == 0) {
      for (std::size_t l = 0; l < kL; ++l) uniform[j][l] = inputs[j].data[0];
      base[j] = uniform[j];
      mask[j] = 0;
    } else {
      base[j] = inputs[j].data;
      mask[j] = ~std::size_t(0);
    }
  }
  const std::size_t full = n - n % kL;
  run_full_batches<K, W>(base, mask, outputs, full, std::make_index_sequence<kIn>{},
                         std::make_index_sequence<kOut>{});
  if (full == n) return;
  // The partial last batch, padded with its first row (load_column).
  const std::size_t count = n - full;
  W x[kIn];
  W y[kOut];
  for (std::size_t j = 0; j < kIn; ++j) x[j] = load_column<W>(inputs[j], full, count);
  K::template eval<W>(x, y);
  alignas(64) S tmp[kL];
  for (std::size_t k = 0; k < kOut; ++k) {
    store_lanes(tmp, y[k]);
    for (std::size_t l = 0; l < count; ++l) outputs[k][full + l] = tmp[l];
  }
}

// Output k of rows [i, i + count): full batches stored directly, a partial one through a buffer.
template <class W, class S>
GLINTLAB_FN void store_rows(S* out, std::size_t i, std::size_t count, const W& w) {
  constexpr std::size_t kL = kLanesOf<W>;
  if (count == kL) {
    store_lanes(out + i, w);
    return;
  }
  alignas(64) S tmp[kL];
  store_lanes(tmp, w);
  for (std::size_t l = 0; l < count; ++l) out[i + l] = tmp[l];
}

// q: kQueryColumnsWithCorners columns in layout order (model_batch.cpp pads a query without
// corners with zero columns); the corners are loaded only for the models that read them.
template <class W, bool kCorners, class S>
GLINTLAB_FN ModelQuery<W> load_query(const Column<S>* q, std::size_t i, std::size_t count) {
  ModelQuery<W> r;
  for_each_query_column(r, [&](std::size_t k, const QueryColumn& c, W& member) {
    member = kCorners || c.part != QueryPart::kCorners ? load_column<W>(q[k], i, count) : W(0);
  });
  return r;
}

template <class M>
inline constexpr bool kReadsCorners = (M::kNeeds & kNeedsPixelCorners) != 0;

// Output k of rows [i, i + count) where the batch's lane belongs to group g of `lanes` (a batch
// run once per group of its lanes' parameters, core/simd/lane_params.h).
template <class W, class S, class L>
GLINTLAB_FN void store_group_rows(S* out, std::size_t i, std::size_t count, const W& w,
                                  const L& lanes, std::size_t g) {
  constexpr std::size_t kL = kLanesOf<W>;
  alignas(64) S tmp[kL];
  store_lanes(tmp, w);
  for (std::size_t l = 0; l < count; ++l)
    if (lanes.group_of(l) == g) out[i + l] = tmp[l];
}

// The parameters of a model batch driver: one vector for every row (`values`), or a column per
// parameter (`columns`, stride 0 or 1), whose lanes::LaneParams give each batch's lanes their own
// rows' values, in groups of lanes that can share a Params<W> (one group unless uniform members
// such as a choice differ between the batch's rows).
template <class M, class W>
class DriverParams {
 public:
  using P = typename M::template Params<W>;
  DriverParams(const double* values, const Column<double>* columns) : columns_(columns) {
    if (columns_ == nullptr) {
      uniform_ = M::template params<W>(std::span<const double>(values, M::kParams.size()));
    } else {
      lanes_.emplace();
    }
  }
  // Batch [i, i + count): its groups.
  std::size_t load(std::size_t i, std::size_t count) {
    if (columns_ == nullptr) return 1;
    lanes_->load(columns_, i, count);
    return lanes_->groups();
  }
  const P& group(std::size_t g) const { return columns_ == nullptr ? uniform_ : lanes_->group(g); }
  // Output rows of group g of the batch [i, i + count) among `groups`.
  template <class S>
  GLINTLAB_FN void store(S* out, std::size_t i, std::size_t count, const W& w, std::size_t groups,
                         std::size_t g) const {
    if (groups == 1)
      store_rows(out, i, count, w);
    else
      store_group_rows(out, i, count, w, *lanes_, g);
  }

 private:
  const Column<double>* columns_;
  P uniform_{};
  std::optional<lanes::LaneParams<M, W>> lanes_;
};

// One driver body for both parameter forms, kept out of line (internal linkage): the model's
// kernels then have one call site per instantiation, as before per-row parameters existed, so
// the compiler inlines them as it did (no out-of-line copy with vague linkage in an ISA unit).
template <class M, class W, class S>
__attribute__((noinline)) void model_eval_rows(const double* values, const Column<double>* columns,
                                               const Column<S>* query, S* const* outputs,
                                               std::size_t n) {
  constexpr std::size_t kL = kLanesOf<W>;
  DriverParams<M, W> p(values, columns);  // uniform values converted to W once
  for (std::size_t i = 0; i < n; i += kL) {
    const std::size_t count = n - i < kL ? n - i : kL;
    const std::size_t groups = p.load(i, count);
    const ModelQuery<W> q = load_query<W, kReadsCorners<M>>(query, i, count);
    for (std::size_t g = 0; g < groups; ++g) {
      const auto r = M::template eval<W>(p.group(g), q);
      p.store(outputs[0], i, count, r.value, groups, g);
      p.store(outputs[1], i, count, r.pdf, groups, g);
      for (std::size_t k = 0; k < r.intermediates.size(); ++k)
        p.store(outputs[2 + k], i, count, r.intermediates[k], groups, g);
    }
  }
}

// query: as for model_eval_rows, then the two uniform columns.
template <class M, class W, class S>
__attribute__((noinline)) void model_sample_rows(const double* values,
                                                 const Column<double>* columns,
                                                 const Column<S>* query, S* const* outputs,
                                                 std::size_t n) {
  constexpr std::size_t kL = kLanesOf<W>;
  const Column<S>* u = query + kQueryColumnsWithCorners;
  DriverParams<M, W> p(values, columns);
  for (std::size_t i = 0; i < n; i += kL) {
    const std::size_t count = n - i < kL ? n - i : kL;
    const std::size_t groups = p.load(i, count);
    const Vec2<W> uv{load_column<W>(u[0], i, count), load_column<W>(u[1], i, count)};
    const ModelQuery<W> q = load_query<W, kReadsCorners<M>>(query, i, count);
    for (std::size_t g = 0; g < groups; ++g) {
      const ModelSample<W> s = M::template sample<W>(p.group(g), q, uv);
      p.store(outputs[0], i, count, s.wo.x, groups, g);
      p.store(outputs[1], i, count, s.wo.y, groups, g);
      p.store(outputs[2], i, count, s.wo.z, groups, g);
      p.store(outputs[3], i, count, s.pdf, groups, g);
      p.store(outputs[4], i, count, s.weight, groups, g);
      p.store(outputs[5], i, count, from_mask<W>(s.rejected), groups, g);
    }
  }
}

// A model's batch with parameter values uniform over the call.
template <class M, class W, class S>
void run_model_eval(const double* params, const Column<S>* query, S* const* outputs,
                    std::size_t n) {
  model_eval_rows<M, W, S>(params, nullptr, query, outputs, n);
}
template <class M, class W, class S>
void run_model_sample(const double* params, const Column<S>* query, S* const* outputs,
                      std::size_t n) {
  model_sample_rows<M, W, S>(params, nullptr, query, outputs, n);
}
// The same with a parameter column per parameter (stride 0 or 1), each row with its own values.
template <class M, class W, class S>
void run_model_eval_lanes(const Column<double>* params, const Column<S>* query, S* const* outputs,
                          std::size_t n) {
  model_eval_rows<M, W, S>(nullptr, params, query, outputs, n);
}
template <class M, class W, class S>
void run_model_sample_lanes(const Column<double>* params, const Column<S>* query,
                            S* const* outputs, std::size_t n) {
  model_sample_rows<M, W, S>(nullptr, params, query, outputs, n);
}

template <class K, class WF, class WFF, class WD>
constexpr BatchFns kernel_fns() {
  return {&run_kernel<K, WF, float>, &run_kernel<K, WFF, float>, &run_kernel<K, WD, double>,
          nullptr, nullptr, nullptr};
}

// Whether M's kernels, as declared, take the batch type W: params, eval and sample as the batch
// drivers above call them. (A kernel declared for every T whose body does not compile for W, an
// `if` on a per-lane value, is not visible here: the compiler reports that in the body.)
template <class M, class W>
concept KernelsTakeBatch = requires(std::span<const double> v, const ModelQuery<W>& q, Vec2<W> u) {
  { M::template params<W>(v) } -> std::same_as<typename M::template Params<W>>;
  {
    M::template eval<W>(M::template params<W>(v), q)
    } -> std::same_as<ModelEval<W, M::kIntermediates.size()>>;
  { M::template sample<W>(M::template params<W>(v), q, u) } -> std::same_as<ModelSample<W>>;
};

// One message for a model that does not take the batch types, instead of an error per kernel
// call and batch type; the compiler names the model in the instantiation of this struct.
template <class M, class WF, class WFF, class WD>
struct ModelKernelsOnSimdBatches {
  static constexpr bool kTake =
      KernelsTakeBatch<M, WF> && KernelsTakeBatch<M, WFF> && KernelsTakeBatch<M, WD>;
  static_assert(kTake,
                "this model's kernels (params, eval, sample) cannot be instantiated on the SIMD "
                "batch types (Wide<>): write them as templates on the float type with select() "
                "instead of branches on per-lane values (docs/adding_a_model.md, Kernels), or "
                "declare `static constexpr bool kBatched = false;` in the model so that its "
                "batches loop over its double kernels");
};

template <class M, class WF, class WFF, class WD>
constexpr BatchFns model_eval_fns() {
  if constexpr (ModelKernelsOnSimdBatches<M, WF, WFF, WD>::kTake) {
    return {&run_model_eval<M, WF, float>,        &run_model_eval<M, WFF, float>,
            &run_model_eval<M, WD, double>,       &run_model_eval_lanes<M, WF, float>,
            &run_model_eval_lanes<M, WFF, float>, &run_model_eval_lanes<M, WD, double>};
  } else {
    return BatchFns{};  // (refused above; nothing more to report)
  }
}
template <class M, class WF, class WFF, class WD>
constexpr BatchFns model_sample_fns() {
  if constexpr (ModelKernelsOnSimdBatches<M, WF, WFF, WD>::kTake) {
    return {&run_model_sample<M, WF, float>,        &run_model_sample<M, WFF, float>,
            &run_model_sample<M, WD, double>,       &run_model_sample_lanes<M, WF, float>,
            &run_model_sample_lanes<M, WFF, float>, &run_model_sample_lanes<M, WD, double>};
  } else {
    return BatchFns{};
  }
}

// A double-only model (kDoubleOnly) runs on the double batches whatever the column type: float
// columns are widened on load and the results rounded on store, as the scalar loop over its
// double thunks does; fast math (a float policy) does not apply.
template <class M, class WF, class WD>
using FloatBatchOf = std::conditional_t<glintlab::detail::DoubleOnly<M>, WD, WF>;

// The table of one ISA, in the entry order of core/simd/table.h. WF: its exact float type, WFF:
// its fast float type, WD: its exact double type.
template <class WF, class WFF, class WD, class... Ms>
const BatchFns* make_table(ModelList<Ms...>) {
#define GLINTLAB_KERNEL_ENTRY(K) kernel_fns<K, WF, WFF, WD>(),
  static constexpr BatchFns kTable[] = {
      GLINTLAB_SIMD_KERNELS(GLINTLAB_KERNEL_ENTRY)
          model_eval_fns<Ms, FloatBatchOf<Ms, WF, WD>, FloatBatchOf<Ms, WFF, WD>, WD>()...,
      model_sample_fns<Ms, FloatBatchOf<Ms, WF, WD>, FloatBatchOf<Ms, WFF, WD>, WD>()...};
#undef GLINTLAB_KERNEL_ENTRY
  return kTable;
}
template <class WF, class WFF, class WD>
const BatchFns* make_isa_table() {
  return make_table<WF, WFF, WD>(BatchedModels{});
}
// The table of an xsimd architecture A.
template <class A>
const BatchFns* make_xsimd_table() {
  return make_isa_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                        Wide<xsimd::batch<double, A>>>();
}

}  // namespace
}  // namespace glintlab::simd::detail
