// SSE4.2 instantiation of every batch kernel and batched model (4 floats / 2 doubles; compiled with
// -msse4.2).
#if !defined(__SSE4_2__)
#error "isa_sse42.cpp must be compiled with -msse4.2 (core/CMakeLists.txt)"
#endif
#define GLINTLAB_SIMD_TU sse42
#include "core/simd/instantiate.h"

namespace glintlab::simd::detail {

const BatchFns* table_sse42() { return make_xsimd_table<xsimd::sse4_2>(); }

}  // namespace glintlab::simd::detail
