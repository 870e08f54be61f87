// The per-ISA dispatch table behind eval_batch: one function pointer per kernel and flavour.
#pragma once

#include <cstddef>

#include "core/simd/batch.h"

namespace glintlab::simd::detail {

template <class S>
using BatchFn = void (*)(const Column<S>* inputs, S* const* outputs, std::size_t n);

struct IsaTable {
  const BatchFn<float>* exact_float;  // kernel_count() entries each
  const BatchFn<float>* fast_float;
  const BatchFn<double>* exact_double;
};

// Defined in isa_scalar.cpp, isa_sse42.cpp, isa_avx2.cpp, isa_avx512.cpp.
const IsaTable& table_scalar();
const IsaTable& table_sse42();
const IsaTable& table_avx2();
const IsaTable& table_avx512();

}  // namespace glintlab::simd::detail
