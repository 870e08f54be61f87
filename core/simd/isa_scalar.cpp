// Scalar instantiation of every batch kernel and batched model: plain float/double (exact) and
// Wide<float, FastMath>.
#define GLINTLAB_SIMD_TU scalar
#include "core/simd/instantiate.h"
#include "core/simd/model_instantiate.h"

namespace glintlab::simd::detail {

const IsaTable& table_scalar() { return make_table<float, Wide<float, FastMath>, double>(); }

const ModelFns* model_table_scalar() {
  return make_model_table<float, Wide<float, FastMath>, double>(BatchedModels{});
}

}  // namespace glintlab::simd::detail
