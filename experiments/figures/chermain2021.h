// Figure experiments of Chermain et al. 2021, "Real-Time Geometric Glint Anti-Aliasing with Normal
// Map Filtering" (with the 2020 glinty BRDF it extends).
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry chermain2021_fig3_entry();   // Fig. 3: dictionary levels converging to the Gaussian
FigureEntry chermain2021_fig7_entry();   // Fig. 7: no LEAN / LEAN rho = 0 / LEAN with rho
FigureEntry chermain2021_fig8_entry();   // Fig. 8: curved tubes with and without GGAA
FigureEntry chermain2021_fig9_entry();   // Fig. 9: Eq. 20 vs Eq. 21, s_K 0.5 vs 1, shimmer
FigureEntry chermain2021_fig10_entry();  // Fig. 10: rho in {0, 0.5, 0.99} at e^15 and e^50

}  // namespace glintlab::experiments
