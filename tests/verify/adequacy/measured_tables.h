// The measured tables the chooser tests judge a chooser by (chermain_chooser_test.cpp,
// kemppinen_chooser_test.cpp, cost_chooser_test.cpp): each measured as `glintlab adequacy` decides
// a table, at fewer positions than the table's so that a test takes seconds.
#pragma once

#include <vector>

#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/kemppinen_adequacy.h"

namespace glintlab::verify::adequacy {

// The Chermain quick grid's 264 cells at 2000 positions (the table measures 8000; its counts are
// in docs/adequacy.md), decided at `tau` over the table's eight decisions per cell.
inline std::vector<ChermainCellResult> measured_chermain_quick_grid(double tau) {
  ChermainGridAxes a = chermain_grid_axes(Budget::kQuick);
  a.samples = 2000;
  const auto cells = make_chermain_grid({"chermain"}, a);
  return measure_chermain_grid(cells, a.samples, decision_for_decisions(cells.size() * 8, tau));
}

// 32 Kemppinen cells (kemppinen_ggx; 10 .. 1e5 points per footprint, α 0.1 and 0.3, θ_i 0° and
// 60°, two half-vector angles) at 1500 positions, decided at `tau` likewise.
inline std::vector<KemppinenCellResult> measured_kemppinen_small_grid(double tau) {
  KemppinenGridAxes a;
  a.points = {10, 1e3, 1e4, 1e5};
  a.alpha = {0.1, 0.3};
  a.theta_i_deg = {0, 60};
  a.theta_h_count = 2;
  const auto cells = make_kemppinen_grid({"kemppinen_ggx"}, a);
  return measure_kemppinen_grid(cells, 1500, decision_for_decisions(cells.size() * 8, tau));
}

}  // namespace glintlab::verify::adequacy
