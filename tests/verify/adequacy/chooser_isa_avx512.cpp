// The choosers of chooser_isa.h on xsimd::avx512bw batches, with this ISA's flags
// (tests/CMakeLists.txt).
#define GLINTLAB_CHOOSER_RAW(S) xsimd::batch<S, xsimd::avx512bw>
#define GLINTLAB_CHOOSER_NAME chooser_isa_avx512
#include "verify/adequacy/chooser_isa.inc"
