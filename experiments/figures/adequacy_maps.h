// Figure adequacy-maps: the cheapest adequate level of each glint family over the adequacy grid's
// axes (verify/adequacy/binomial_adequacy.h), as labelled category maps. Only the binomial family
// (deliot_belcour, kneiphof_klein) has measured levels so far.
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry adequacy_maps_entry();

}  // namespace glintlab::experiments
