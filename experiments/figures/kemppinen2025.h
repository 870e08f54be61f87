// Figure experiments of Kemppinen et al. 2025, "Evaluating and Sampling Glinty NDFs in Constant
// Time": D★ on U_Ω and Ω (Fig. 2–3), blending (Fig. 6), parameter sweeps (Fig. 10), limitations
// (Fig. 14), furnace (Fig. 15).
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry kemppinen2025_fig2_3_entry();  // Fig. 2–3: D★^f on the disk and the hemisphere
FigureEntry kemppinen2025_fig6_entry();    // Fig. 6: roulette vs linear MIP blending
FigureEntry kemppinen2025_fig10_entry();   // Fig. 10: one sweep per parameter (Table 1)
FigureEntry kemppinen2025_fig14_entry();   // Fig. 14: k = 4 vs 16; microroughness too high
FigureEntry kemppinen2025_fig15_entry();   // Fig. 15: area-averaged white furnace over θo
FigureEntry kemppinen2025_fig7_entry();    // Fig. 7: env-light convergence (kemppinen2025_fig7.cpp)

}  // namespace glintlab::experiments
