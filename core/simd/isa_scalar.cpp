// Scalar instantiation of every batch kernel: plain float/double (exact) and Wide<float, FastMath>.
#define GLINTLAB_SIMD_TU scalar
#include "core/simd/instantiate.h"

namespace glintlab::simd::detail {

const IsaTable& table_scalar() { return make_table<float, Wide<float, FastMath>, double>(); }

}  // namespace glintlab::simd::detail
