// AVX-512 (F, CD, DQ, BW) instantiation of every batch kernel and batched model (16 floats / 8
// doubles).
#if !defined(__AVX512F__) || !defined(__AVX512BW__) || !defined(__AVX512DQ__)
#error "isa_avx512.cpp must be compiled with -mavx512f -mavx512cd -mavx512dq -mavx512bw"
#endif
#define GLINTLAB_SIMD_TU avx512
#include "core/simd/instantiate.h"
#include "core/simd/model_instantiate.h"

namespace glintlab::simd::detail {

const IsaTable& table_avx512() {
  using A = xsimd::avx512bw;
  return make_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                    Wide<xsimd::batch<double, A>>>();
}

const ModelFns* model_table_avx512() {
  using A = xsimd::avx512bw;
  return make_model_table<Wide<xsimd::batch<float, A>>, Wide<xsimd::batch<float, A>, FastMath>,
                          Wide<xsimd::batch<double, A>>>(BatchedModels{});
}

}  // namespace glintlab::simd::detail
