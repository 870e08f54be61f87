// The example glint model of docs/adding_a_model.md (tests/experiments/example_glint_model.h) as a
// plug-in: the whole plug-in source. Built in the build tree (tests/CMakeLists.txt, for
// tests/cli/plugin_test.cpp) and against an installed glintlab (tests/install/plugin).
#include <glintlab/plugin.h>

#include "experiments/example_glint_model.h"

GLINTLAB_PLUGIN(glintlab::example::ExampleGlints);
