// A plug-in whose model is named like a built-in one (smooth_ggx): the loader must refuse it.
#include <glintlab/plugin.h>

#include "core/models/smooth_ggx.h"

GLINTLAB_PLUGIN(glintlab::SmoothGGX);
