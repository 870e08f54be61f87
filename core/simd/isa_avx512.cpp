// AVX-512 (F, CD, DQ, BW) instantiation of every batch kernel and batched model (16 floats / 8
// doubles).
#if !defined(__AVX512F__) || !defined(__AVX512BW__) || !defined(__AVX512DQ__)
#error "isa_avx512.cpp must be compiled with -mavx512f -mavx512cd -mavx512dq -mavx512bw"
#endif
#define GLINTLAB_SIMD_TU avx512
#include "core/simd/instantiate.h"

namespace glintlab::simd::detail {

const BatchFns* table_avx512() { return make_xsimd_table<xsimd::avx512bw>(); }

}  // namespace glintlab::simd::detail
