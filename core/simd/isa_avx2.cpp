// AVX2 + FMA instantiation of every batch kernel and batched model (8 floats / 4 doubles; -mavx2
// -mfma).
#if !defined(__AVX2__) || !defined(__FMA__)
#error "isa_avx2.cpp must be compiled with -mavx2 -mfma (core/CMakeLists.txt)"
#endif
#define GLINTLAB_SIMD_TU avx2
#include "core/simd/instantiate.h"
#include "core/simd/model_instantiate.h"

namespace glintlab::simd::detail {

const IsaTable& table_avx2() {
  using A = xsimd::fma3<xsimd::avx2>;
  return make_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                    Wide<xsimd::batch<double, A>>>();
}

const ModelFns* model_table_avx2() {
  using A = xsimd::fma3<xsimd::avx2>;
  return make_model_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                          Wide<xsimd::batch<double, A>>>(BatchedModels{});
}

}  // namespace glintlab::simd::detail
