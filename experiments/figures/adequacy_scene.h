// Figure adequacy-scene: the validation scenes of claim adequacy.choice-is-safe
// (verify/scenes/adequacy_scenes.h) side by side — each pixel rendered with the level the engine
// chooser picks, the most complete level everywhere, the per-pixel difference against TAU, and the
// chosen level; the binomial family (deliot_belcour, kneiphof_klein; most complete: exact
// counting) and the Kemppinen family (kemppinen_ggx; k16_exact).
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry adequacy_scene_entry();

}  // namespace glintlab::experiments
