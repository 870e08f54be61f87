// Figure experiments of Eto & Tokuyoshi 2023, "Bounded VNDF Sampling for Smith–GGX Reflections".
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry eto2023_fig4_entry();      // Fig. 4: spherical vs bounded caps at equal spp, RMSE
FigureEntry eto2023_rmse_spp_entry();  // RMSE vs spp (log-log) of the Fig. 4 scene

}  // namespace glintlab::experiments
