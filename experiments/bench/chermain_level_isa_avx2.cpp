// Chermain::eval for the adequacy benchmark's Chermain levels on xsimd::fma3<xsimd::avx2> batches, with this ISA's flags
// (experiments/bench/CMakeLists.txt).
#define GLINTLAB_CHERMAIN_LEVEL_RAW xsimd::batch<double, xsimd::fma3<xsimd::avx2>>
#define GLINTLAB_CHERMAIN_LEVEL_NAME chermain_level_isa_avx2
#include "experiments/bench/chermain_level_isa.inc"
