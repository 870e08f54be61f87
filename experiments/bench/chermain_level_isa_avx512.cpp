// Chermain::eval for the adequacy benchmark's Chermain levels on xsimd::avx512bw batches, with this ISA's flags
// (experiments/bench/CMakeLists.txt).
#define GLINTLAB_CHERMAIN_LEVEL_RAW xsimd::batch<double, xsimd::avx512bw>
#define GLINTLAB_CHERMAIN_LEVEL_NAME chermain_level_isa_avx512
#include "experiments/bench/chermain_level_isa.inc"
