// The one per-ISA dispatch table behind both batch APIs (core/simd/batch.h for kernels,
// core/simd/model_batch.h for models): one function signature, so one table, one ISA switch and
// one argument check serve both.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>

#include "core/model_list.h"
#include "core/simd/batch.h"

namespace glintlab::simd::detail {

// params: a model's kParams values (kernels take theirs as stride-0 columns and ignore it);
// in: a kernel's input columns, or a model's query columns (kQueryLayout order, corners included)
// followed, for sample, by the two uniform columns.
template <class S>
using BatchFn = void (*)(const double* params, const Column<S>* in, S* const* out, std::size_t n);

// A model's batch with a parameter column per parameter (kParams order; stride 0: one value for
// every row, stride 1: row i's value at data[i]), each row evaluated with its own values.
template <class S>
using LaneBatchFn = void (*)(const Column<double>* params, const Column<S>* in, S* const* out,
                             std::size_t n);

// One entry's instantiations; Math::kFast picks fast_float. The lanes_ ones: a model's entries
// only (null for a kernel).
struct BatchFns {
  BatchFn<float> exact_float, fast_float;
  BatchFn<double> exact_double;
  LaneBatchFn<float> lanes_exact_float, lanes_fast_float;
  LaneBatchFn<double> lanes_exact_double;
};

// One plug-in model's instantiations (ModelEntry::plugin_batches), compiled in the plug-in
// (glintlab/plugin.h), indexed by Isa; nullptr for an ISA the plug-in was built without, which
// then runs the entry's double thunks row by row.
struct ModelBatchFns {
  std::array<const BatchFns*, 4> eval, sample;
};

// The entries of each ISA's table, in this order: every kernel (GLINTLAB_SIMD_KERNELS order),
// then the eval of each model of BatchedModels (core/model_list.h), then the sample of each.
inline std::size_t model_eval_entry(std::size_t m) {
  return static_cast<std::size_t>(kernel_count()) + m;
}
inline std::size_t model_sample_entry(std::size_t m) {
  return model_eval_entry(BatchedModels::kSize + m);
}

// Defined in isa_scalar.cpp, isa_sse42.cpp, isa_avx2.cpp, isa_avx512.cpp.
const BatchFns* table_scalar();
const BatchFns* table_sse42();
const BatchFns* table_avx2();
const BatchFns* table_avx512();

// The checks every batch call shares, after its own column counts: each column's stride is 0 or
// 1 (`label(j)` names column j in the message), the CPU has `isa`, fast math only with float.
// Messages start with `what` ("eval_batch", "sample_batch").
template <class S>
void check_call(const char* what, std::span<const Column<S>> in, std::string (*label)(std::size_t),
                Isa isa, Math math);

// Runs entry `entry` of isa's table on checked arguments.
template <class S>
void run(std::size_t entry, const double* params, const Column<S>* in, S* const* out, std::size_t n,
         Isa isa, Math math);
// Runs the lanes_ function of model entry `entry` of isa's table on checked arguments.
template <class S>
void run_lanes(std::size_t entry, const Column<double>* params, const Column<S>* in, S* const* out,
               std::size_t n, Isa isa, Math math);

}  // namespace glintlab::simd::detail
