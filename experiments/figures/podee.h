// Figure experiments of Podee, Max, Iwasaki & Dobashi, "Micro-specular-highlight real-time
// rendering" (Sec. 4, Fig. 4, Table 1).
#pragma once

#include <memory>

#include "experiments/figures/figure_registry.h"

namespace glintlab::podee {
struct NormalMap;
}

namespace glintlab::experiments {

FigureEntry podee_table1_entry();         // Table 1: RMSE of centre / LEAN / method vs reference
FigureEntry podee_fig4_distance_entry();  // Fig. 4 / Sec. 4: error vs camera distance
FigureEntry podee_fig4_flicker_entry();   // Sec. 4 stability: flicker under sub-pixel motion

// The sphere's normal map in view `view` of a panel of `views` × `views` views (row by row from the
// top left), each at the experiment's pixel footprint, so that a larger panel shows more of the
// surface rather than smaller pixels: podee::normal_map() translated by (du, dv) =
// (view mod views, view div views) / views of a tile, h'(u, v) = h(u + du, v + dv) (a tile spans
// 45° both ways: a turn of the sphere about its axis by 45° du and a shift along its meridians by
// 45° dv): the same bumps, another part of them under the highlight, with its LEAN moments rebuilt
// from the translated field. View 0 is podee::normal_map() itself.
std::shared_ptr<const podee::NormalMap> podee_view_normal_map(int view, int views);

}  // namespace glintlab::experiments
