// Scalar instantiation of every batch kernel and batched model: plain float/double (exact) and
// Wide<float, FastMath>.
#define GLINTLAB_SIMD_TU scalar
#include "core/simd/instantiate.h"

namespace glintlab::simd::detail {

const BatchFns* table_scalar() { return make_isa_table<float, Wide<float, FastMath>, double>(); }

}  // namespace glintlab::simd::detail
