// The measured cost of every registered figure; see figure_costs.h.
#include "cli/figure_costs.h"

#include <algorithm>

namespace glintlab::cli {

// CPU seconds (user + system, GNU time) of `glintlab figure ID --budget B --threads 1`, release
// build, 2026-12-05, on the shared 2-core machine of docs/building.md under load (CPU time, not
// wall time, so that the load matters little), one run each. Some full rows are the CPU times
// recorded in experiments/README.md ("Image sizes per budget": eto2023-fig4 and -fig4-rmse-spp,
// kneiphof2024-fig9, kemppinen2025-fig7, and podee-*, chermain2021-fig7/-fig8/-fig9 as measured
// when their panels became 512 pixels or more) and adequacy-scene's the one in docs/adequacy.md.
// kneiphof2024-table1 runs under the clock's 0.01 s resolution (no benchmark JSON) and is
// recorded as 0.01. kemppinen2025-fig2-3, -fig6, -fig14 and podee-fig4-flicker re-measured at
// quick on 2026-12-06 once their maps became matplotlib heat maps (the script's CPU included);
// their full rows are the recorded ones plus that drawing's CPU at quick (a map has at most
// 128 x 128 cells at either budget), not re-run. adequacy-scene's quick row since its area scenes
// (2026-12-06): the recorded 17.5 times the ratio of the new to the old build's CPU measured back
// to back under the same load (25.37 s / 23.55 s); its full row the recorded 203 plus 8 times the
// area scenes' quick CPU (4x the pixels, 2x the realisations), not re-run. adequacy-maps' rows
// since it draws the area family: the recorded 5.14 and 250 times the ratio of the new to the old
// build's quick CPU measured back to back under the same load (15.32 s / 7.85 s); the full row
// not re-run; since it draws the Chermain family too, both rows times that figure's quick CPU ratio
// (33 s / 15.5 s, measured by the change's author at load 3-4); since it draws the Kemppinen
// family too (at 1000 positions per cell at quick), both rows times the ratio of its quick CPU
// then, 62.2 s (2026-12-07, load 2-6), to that 33 s: the full row not re-run, so its Kemppinen
// part is scaled, not measured. Only the ratios matter: the shards' balance, never a verdict or an output,
// depends on these numbers. Re-measure a row when its figure's budget changes.
const std::vector<FigureCost>& figure_costs() {
  // clang-format off
  static const std::vector<FigureCost> kCosts = {
      // id                             quick    full
      {"eto2023-fig4",                    2.18,    138},
      {"eto2023-fig4-rmse-spp",           2.80,    161},
      {"models-hemisphere",               1.21,   5.93},
      {"podee-table1",                    2.06,    185},
      {"podee-fig4-distance",             2.05,    548},
      {"podee-fig4-flicker",              6.80,    377},
      {"kneiphof2024-fig6",               0.07,   0.94},
      {"kneiphof2024-fig9",               9.26,    231},
      {"kneiphof2024-fig10",              0.62,   66.8},
      {"kneiphof2024-table1",             0.01,   0.01},
      {"chermain2021-fig3",               0.95,   0.97},
      {"chermain2021-fig7",               1.71,    354},
      {"chermain2021-fig8",               1.81,    147},
      {"chermain2021-fig9",               1.81,    179},
      {"chermain2021-fig10",              1.03,   2.32},
      {"kemppinen2025-fig2-3",            2.60,   10.1},
      {"kemppinen2025-fig6",              0.65,   2.86},
      {"kemppinen2025-fig10",             0.79,   13.4},
      {"kemppinen2025-fig14",             0.59,   2.25},
      {"kemppinen2025-fig15",             0.11,   4.89},
      {"kemppinen2025-table3",            0.28,   6.73},
      {"kemppinen2025-speed-accuracy",    1.85,   23.2},
      {"kemppinen2025-fig7",             18.48,    588},
      {"adequacy-maps",                   40.1,   1956},
      {"adequacy-scene",                  18.9,    218},
  };
  // clang-format on
  return kCosts;
}

double figure_cost_seconds(std::string_view id, bool quick) {
  const std::vector<FigureCost>& costs = figure_costs();
  const auto it =
      std::find_if(costs.begin(), costs.end(), [&](const FigureCost& c) { return c.id == id; });
  if (it != costs.end()) return quick ? it->quick_seconds : it->full_seconds;
  double sum = 0;
  for (const FigureCost& c : costs) sum += quick ? c.quick_seconds : c.full_seconds;
  return costs.empty() ? 1.0 : sum / double(costs.size());
}

}  // namespace glintlab::cli
