// The plug-in's one translation unit: registers the model of zirr_kaplanyan.h with glintlab when
// the module is loaded (glintlab --plugin PATH, or the GLINTLAB_PLUGINS variable).
#include <glintlab/plugin.h>

#include "zirr_kaplanyan.h"

GLINTLAB_PLUGIN(glintlab::zk16::ZirrKaplanyan);
