// The choosers of chooser_isa.h on xsimd::sse4_2 batches, with this ISA's flags
// (tests/CMakeLists.txt).
#define GLINTLAB_CHOOSER_RAW(S) xsimd::batch<S, xsimd::sse4_2>
#define GLINTLAB_CHOOSER_NAME chooser_isa_sse42
#include "verify/adequacy/chooser_isa.inc"
