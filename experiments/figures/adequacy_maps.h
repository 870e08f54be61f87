// Figure adequacy-maps: the cheapest adequate level of each glint family over the adequacy grid's
// axes (verify/adequacy/), as labelled category maps: the binomial, Kemppinen, area and Chermain
// families, each map named with its family in summary.md and the CSVs.
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry adequacy_maps_entry();

}  // namespace glintlab::experiments
