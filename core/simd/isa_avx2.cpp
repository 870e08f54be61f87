// AVX2 + FMA instantiation of every batch kernel and batched model (8 floats / 4 doubles; -mavx2
// -mfma).
#if !defined(__AVX2__) || !defined(__FMA__)
#error "isa_avx2.cpp must be compiled with -mavx2 -mfma (core/CMakeLists.txt)"
#endif
#define GLINTLAB_SIMD_TU avx2
#include "core/simd/instantiate.h"

namespace glintlab::simd::detail {

const BatchFns* table_avx2() { return make_xsimd_table<xsimd::fma3<xsimd::avx2>>(); }

}  // namespace glintlab::simd::detail
