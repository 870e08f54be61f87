// Figure experiments of Kneiphof & Klein 2024, "Real-Time Rendering of Glints in the Presence of
// Area Lights" (core/glints/kneiphof.h, deliot_belcour.h).
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry kneiphof2024_fig6_entry();    // Fig. 6: cap probability vs Deliot & Belcour's fitted R
FigureEntry kneiphof2024_fig9_entry();    // Fig. 9: subdivided light, MC vs shared-lobe terms
FigureEntry kneiphof2024_fig10_entry();   // Fig. 10: convergence as N_P quadruples
FigureEntry kneiphof2024_table1_entry();  // Table 1 analogue: time per evaluation

}  // namespace glintlab::experiments
