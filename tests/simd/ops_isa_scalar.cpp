// The ops of ops_isa.h on float and double: the scalar ops layer (core/math/ops.h), the reference.
#define GLINTLAB_OPS_WIDE(S) S
#define GLINTLAB_OPS_NAME isa_ops_scalar
#include "simd/ops_isa.inc"
