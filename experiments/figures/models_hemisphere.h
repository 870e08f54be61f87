// The registry-driven figure `models-hemisphere`: value and pdf of every registered model on the
// hemisphere of ωo (no paper figure; a look at any model, new ones included, with no code).
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry models_hemisphere_entry();

}  // namespace glintlab::experiments
