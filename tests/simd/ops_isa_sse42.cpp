// The ops of ops_isa.h on xsimd::sse4_2 batches (compiled with this ISA's flags, tests/CMakeLists.txt).
#define GLINTLAB_OPS_WIDE(S) ::glintlab::Wide<xsimd::batch<S, xsimd::sse4_2>>
#define GLINTLAB_OPS_NAME isa_ops_sse42
#include "simd/ops_isa.inc"
