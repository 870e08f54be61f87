// The ops of ops_isa.h on xsimd::fma3<xsimd::avx2> batches (compiled with this ISA's flags, tests/CMakeLists.txt).
#define GLINTLAB_OPS_WIDE(S) ::glintlab::Wide<xsimd::batch<S, xsimd::fma3<xsimd::avx2>>>
#define GLINTLAB_OPS_NAME isa_ops_avx2
#include "simd/ops_isa.inc"
