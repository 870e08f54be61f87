// Kemppinen et al. 2025 timing figures read from the Google Benchmark JSON of
// experiments/bench/kemppinen2025_bench.cpp: the Table 3 analogue (time per pixel) and speed vs
// accuracy of D★^f (Eq. 11) against its references, with the cost against footprint size.
#pragma once

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

FigureEntry kemppinen2025_table3_entry();          // Table 3: time per pixel, 3 lights
FigureEntry kemppinen2025_speed_accuracy_entry();  // error vs ns/eval per k, erf; cost vs footprint

}  // namespace glintlab::experiments
