// The per-ISA table of model batch functions behind core/simd/model_batch.h: one entry per model
// of BatchedModels, in list order.
#pragma once

#include <cstddef>

#include "core/simd/batch.h"

namespace glintlab::simd::detail {

// params: the model's kParams.size() values; query: kQueryColumns.size() columns; u: 2 columns.
template <class S>
using ModelEvalFn = void (*)(const double* params, const Column<S>* query, S* const* outputs,
                             std::size_t n);
template <class S>
using ModelSampleFn = void (*)(const double* params, const Column<S>* query, const Column<S>* u,
                               S* const* outputs, std::size_t n);

struct ModelFns {
  ModelEvalFn<float> eval_float, eval_fast_float;
  ModelEvalFn<double> eval_double;
  ModelSampleFn<float> sample_float, sample_fast_float;
  ModelSampleFn<double> sample_double;
};

// BatchedModels::kSize entries each; defined next to the kernel tables in isa_*.cpp.
const ModelFns* model_table_scalar();
const ModelFns* model_table_sse42();
const ModelFns* model_table_avx2();
const ModelFns* model_table_avx512();

}  // namespace glintlab::simd::detail
