// The ops of ops_isa.h on xsimd::avx512bw batches (compiled with this ISA's flags, tests/CMakeLists.txt).
#define GLINTLAB_OPS_WIDE(S) ::glintlab::Wide<xsimd::batch<S, xsimd::avx512bw>>
#define GLINTLAB_OPS_NAME isa_ops_avx512
#include "simd/ops_isa.inc"
