// SSE4.2 instantiation of every batch kernel and batched model (4 floats / 2 doubles; compiled with
// -msse4.2).
#if !defined(__SSE4_2__)
#error "isa_sse42.cpp must be compiled with -msse4.2 (core/CMakeLists.txt)"
#endif
#define GLINTLAB_SIMD_TU sse42
#include "core/simd/instantiate.h"
#include "core/simd/model_instantiate.h"

namespace glintlab::simd::detail {

const IsaTable& table_sse42() {
  using A = xsimd::sse4_2;
  return make_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                    Wide<xsimd::batch<double, A>>>();
}

const ModelFns* model_table_sse42() {
  using A = xsimd::sse4_2;
  return make_model_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                          Wide<xsimd::batch<double, A>>>(BatchedModels{});
}

}  // namespace glintlab::simd::detail
