// Chermain::eval for the adequacy benchmark's Chermain levels on plain double (no batch), with this ISA's flags
// (experiments/bench/CMakeLists.txt).
#define GLINTLAB_CHERMAIN_LEVEL_RAW double
#define GLINTLAB_CHERMAIN_LEVEL_NAME chermain_level_isa_scalar
#include "experiments/bench/chermain_level_isa.inc"
