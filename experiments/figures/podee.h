// Figure experiments of Podee, Max, Iwasaki & Dobashi, "Micro-specular-highlight real-time
// rendering" (Sec. 4, Fig. 4, Table 1).
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry podee_table1_entry();         // Table 1: RMSE of centre / LEAN / method vs reference
FigureEntry podee_fig4_distance_entry();  // Fig. 4 / Sec. 4: error vs camera distance
FigureEntry podee_fig4_flicker_entry();   // Sec. 4 stability: flicker under sub-pixel motion

}  // namespace glintlab::experiments
