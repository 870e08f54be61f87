// The model batch driver: loads SoA query columns into ModelQuery<W>, runs a model's own eval or
// sample template (core/model.h) on W, stores the results. Each ISA translation unit includes this
// after core/simd/instantiate.h and instantiates it for its own W (include in .cpp only).
#pragma once

#include <cstddef>
#include <span>

#include "core/simd/batched_models.h"
#include "core/simd/kernels.h"
#include "core/simd/model_batch.h"
#include "core/simd/model_table.h"

namespace glintlab::simd::detail {
namespace {  // internal linkage, as in instantiate.h

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

// q: kQueryColumnsWithCorners columns in layout order (model_dispatch.cpp pads a query without
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

template <class M, class W, class S>
void run_model_eval(const double* params, const Column<S>* query, S* const* outputs,
                    std::size_t n) {
  constexpr std::size_t kL = kLanesOf<W>;
  // Parameters are uniform over the call: converted to W once.
  const auto p = M::template params<W>(std::span<const double>(params, M::kParams.size()));
  for (std::size_t i = 0; i < n; i += kL) {
    const std::size_t count = n - i < kL ? n - i : kL;
    const auto r = M::template eval<W>(p, load_query<W, kReadsCorners<M>>(query, i, count));
    store_rows(outputs[0], i, count, r.value);
    store_rows(outputs[1], i, count, r.pdf);
    for (std::size_t k = 0; k < r.intermediates.size(); ++k)
      store_rows(outputs[2 + k], i, count, r.intermediates[k]);
  }
}

template <class M, class W, class S>
void run_model_sample(const double* params, const Column<S>* query, const Column<S>* u,
                      S* const* outputs, std::size_t n) {
  constexpr std::size_t kL = kLanesOf<W>;
  const auto p = M::template params<W>(std::span<const double>(params, M::kParams.size()));
  for (std::size_t i = 0; i < n; i += kL) {
    const std::size_t count = n - i < kL ? n - i : kL;
    const Vec2<W> uv{load_column<W>(u[0], i, count), load_column<W>(u[1], i, count)};
    const ModelSample<W> s =
        M::template sample<W>(p, load_query<W, kReadsCorners<M>>(query, i, count), uv);
    store_rows(outputs[0], i, count, s.wo.x);
    store_rows(outputs[1], i, count, s.wo.y);
    store_rows(outputs[2], i, count, s.wo.z);
    store_rows(outputs[3], i, count, s.pdf);
    store_rows(outputs[4], i, count, s.weight);
    store_rows(outputs[5], i, count, from_mask<W>(s.rejected));
  }
}

template <class WF, class WFF, class WD, class M>
constexpr ModelFns model_fns() {
  if constexpr (glintlab::detail::DoubleOnly<M>) {
    // A double-only model (kDoubleOnly) runs on the double batches whatever the column type: float
    // columns are widened on load and the results rounded on store, as the scalar loop over its
    // double thunks does; fast math (a float policy) does not apply.
    return {&run_model_eval<M, WD, float>,   &run_model_eval<M, WD, float>,
            &run_model_eval<M, WD, double>,  &run_model_sample<M, WD, float>,
            &run_model_sample<M, WD, float>, &run_model_sample<M, WD, double>};
  } else {
    return {&run_model_eval<M, WF, float>,    &run_model_eval<M, WFF, float>,
            &run_model_eval<M, WD, double>,   &run_model_sample<M, WF, float>,
            &run_model_sample<M, WFF, float>, &run_model_sample<M, WD, double>};
  }
}

template <class WF, class WFF, class WD, class... Ms>
const ModelFns* make_model_table(ModelList<Ms...>) {
  static constexpr ModelFns kTable[] = {model_fns<WF, WFF, WD, Ms>()...};
  return kTable;
}

}  // namespace
}  // namespace glintlab::simd::detail
