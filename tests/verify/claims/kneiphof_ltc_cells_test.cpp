// kneiphof.ltc-probability's cells and rules (verify/claims/kneiphof/ltc_cells.h), beside the
// typed probe test (claim_probes_test.cpp), which decides the claim from λ = 100 on only: on one
// regime cell the LTC p is within the 10 % of the stronger reading, which a p 20 % off is not
// (a power the rendered rule lacks at high densities); the probability-level rule holds a
// near-truth p and fails a broken one; the rendered rule, over every density, cannot hold the
// near-truth pixel (its resolution limit at λ = 1, why the claim is reported inconclusive) and
// fails broken or brighter pixels.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "verify/check.h"
#include "verify/claims/kneiphof/ltc_cells.h"

namespace glintlab::verify::kneiphof_claims::ltc {
namespace {

constexpr std::uint64_t kSeed = 0x6b6e6569;

// Four regime cells (side 0.5 and 2, mirror, √α 0.5, θv 0° and 40°), MC at 16 × 2048.
std::vector<Cell> regime_cells() {
  std::vector<Cell> cells;
  for (double side : {0.5, 2.0})
    for (double v : {0.0, 40.0})
      cells.push_back(evaluate({side, 0.5, v, 0}, 2048, kSeed, cells.size()));
  return cells;
}

TEST(KneiphofLtcCells, LtcProbabilityWithinTheStrongerReadingsTolerance) {
  const Cell c = evaluate({0.5, 0.5, 40, 0}, 1024, kSeed + 1, 0);
  ASSERT_TRUE(in_regime(c));
  EXPECT_EQ(side(rel_error(c.brdf, c), c), Side::kIn) << rel_error(c.brdf, c);
  EXPECT_EQ(side(rel_error(1.2 * c.brdf, c), c), Side::kOut) << rel_error(1.2 * c.brdf, c);
}

TEST(KneiphofLtcCells, ProbabilityRuleHoldsNearTruthAndFailsBrokenP) {
  const std::vector<Cell> cells = regime_cells();
  const Verdict near = decide(cells, [](const Cell& c) { return c.near_truth; });
  EXPECT_TRUE(is_holding(near)) << to_string(near);
  EXPECT_EQ(decide(cells, [](const Cell& c) { return 1.2 * c.ref; }), Verdict::kFails);
}

TEST(KneiphofLtcCells, RenderedRuleResolutionAndBrokenPixels) {
  const std::vector<Cell> cells = regime_cells();
  // At λ = 1 the rule cannot separate a 3 % error from the truth; from λ = 100 on it can.
  EXPECT_EQ(decide_rendered(cells, near_truth_pixel), Verdict::kFails);
  EXPECT_TRUE(is_holding(decide_rendered(cells, near_truth_pixel, 2)));
  EXPECT_EQ(decide_rendered(cells, brighter_pixel), Verdict::kFails);
  EXPECT_EQ(decide_rendered(cells,
                            [](const Cell& c) {
                              return Rendering{1.2 * c.ref / c.d_h, 1.0};
                            }),
            Verdict::kFails);
  EXPECT_EQ(decide_rendered(cells,
                            [](const Cell& c) {
                              return Rendering{c.ref / c.d_h, 1.04};
                            }),
            Verdict::kFails);
}

}  // namespace
}  // namespace glintlab::verify::kneiphof_claims::ltc
