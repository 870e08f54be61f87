// The choosers of chooser_isa.h on Wide<double> (one lane), the reference unit, with this ISA's flags
// (tests/CMakeLists.txt).
#define GLINTLAB_CHOOSER_RAW(S) S
#define GLINTLAB_CHOOSER_NAME chooser_isa_scalar
#include "verify/adequacy/chooser_isa.inc"
