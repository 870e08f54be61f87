// The choosers of chooser_isa.h on xsimd::fma3<xsimd::avx2> batches, with this ISA's flags
// (tests/CMakeLists.txt).
#define GLINTLAB_CHOOSER_RAW(S) xsimd::batch<S, xsimd::fma3<xsimd::avx2>>
#define GLINTLAB_CHOOSER_NAME chooser_isa_avx2
#include "verify/adequacy/chooser_isa.inc"
