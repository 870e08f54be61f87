// The batch driver: loads SoA columns into one float type W, runs a kernel functor, stores. Each
// ISA translation unit includes this once and instantiates it for its own W (include in .cpp only).
#pragma once

#include <cstddef>
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

#include "core/simd/kernels.h"
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
void run_kernel(const Column<S>* inputs, S* const* outputs, std::size_t n) {
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

// WF: exact float type, WFF: fast float type, WD: exact double type of one ISA.
template <class WF, class WFF, class WD>
const IsaTable& make_table() {
#define GLINTLAB_ENTRY_F(K) &run_kernel<K, WF, float>,
#define GLINTLAB_ENTRY_FF(K) &run_kernel<K, WFF, float>,
#define GLINTLAB_ENTRY_D(K) &run_kernel<K, WD, double>,
  static constexpr BatchFn<float> kExactF[] = {GLINTLAB_SIMD_KERNELS(GLINTLAB_ENTRY_F)};
  static constexpr BatchFn<float> kFastF[] = {GLINTLAB_SIMD_KERNELS(GLINTLAB_ENTRY_FF)};
  static constexpr BatchFn<double> kExactD[] = {GLINTLAB_SIMD_KERNELS(GLINTLAB_ENTRY_D)};
#undef GLINTLAB_ENTRY_F
#undef GLINTLAB_ENTRY_FF
#undef GLINTLAB_ENTRY_D
  static constexpr IsaTable kTable{kExactF, kFastF, kExactD};
  return kTable;
}

}  // namespace
}  // namespace glintlab::simd::detail
