// The adequacy measurement and decision (verify/adequacy/binomial_adequacy.h): the paired
// statistics and their bounds on synthetic values, the decision on clear-cut cells of both models,
// identical results for any thread count, and the chooser against the measured table.
#include "verify/adequacy/binomial_adequacy.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "core/math/rng.h"

namespace glintlab::verify::adequacy {
namespace {

// Values 1 + sd·(a centred uniform scaled to unit variance) at n positions.
std::vector<double> noisy(std::size_t n, double mean, double sd, std::uint64_t seed) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i)
    v[i] = mean + sd * std::sqrt(12.0) * (counter_uniform<double>(seed, i, 0) - 0.5);
  return v;
}

const Decision kDecision{0.02, 3.0};

TEST(AdequacyCompare, IdenticalValuesDifferByNothing) {
  const auto x = noisy(5000, 1, 0.3, 1);
  const LevelStats s = compare_to_exact(x, x, kDecision);
  EXPECT_EQ(s.mean_diff, 0);
  EXPECT_NEAR(s.cv_diff_ucb, 0, 1e-12);
  EXPECT_TRUE(s.adequate);
  EXPECT_NEAR(s.cv, 0.3, 0.01);
}

TEST(AdequacyCompare, ConstantAgainstNoisyDiffersByTheCv) {
  // The smooth level against a reference of CV 0.1: the CV difference is 0.1, far above TAU.
  const auto ref = noisy(20000, 2, 0.2, 2);
  const std::vector<double> flat(ref.size(), 2.0);
  const LevelStats s = compare_to_exact(flat, ref, kDecision);
  EXPECT_NEAR(s.cv_diff, 0.1, 0.003);
  EXPECT_FALSE(s.adequate);
  // A reference of CV 0.005 is within TAU = 0.02 (the bound included).
  const auto calm = noisy(20000, 2, 0.01, 3);
  EXPECT_TRUE(compare_to_exact(flat, calm, kDecision).adequate);
}

TEST(AdequacyCompare, MeanShiftAboveTauIsCaughtBelowIsNot) {
  const auto ref = noisy(20000, 1, 0.05, 4);
  std::vector<double> up3(ref), up1(ref);
  for (double& v : up3) v *= 1.03;
  for (double& v : up1) v *= 1.01;
  const LevelStats a = compare_to_exact(up3, ref, kDecision);
  EXPECT_NEAR(a.mean_diff, 0.03, 1e-9);
  EXPECT_FALSE(a.adequate);
  EXPECT_GT(a.mean_diff_lcb, 0.02);
  const LevelStats b = compare_to_exact(up1, ref, kDecision);
  EXPECT_TRUE(b.adequate);
}

TEST(AdequacyCompare, AllDarkReference) {
  const std::vector<double> zero(100, 0.0), lit(100, 1.0);
  EXPECT_TRUE(compare_to_exact(zero, zero, kDecision).adequate);
  EXPECT_FALSE(compare_to_exact(lit, zero, kDecision).adequate);
}

TEST(AdequacyDecision, BoundLevelSplitsTheFamilyWiseRate) {
  // 1e-3 over 3 decisions per cell: z grows with the number of cells.
  const Decision one = decision_for(1, 0.02), many = decision_for(1000, 0.02);
  EXPECT_NEAR(0.5 * std::erfc(one.z / std::sqrt(2.0)), 1 - std::pow(1 - 1e-3, 1.0 / 3), 1e-9);
  EXPECT_GT(many.z, one.z);
}

TEST(AdequacyCell, LargeFootprintOnPeakIsSmoothOneFacetIsNot) {
  const Decision d = decision_for(4, 0.02);
  // kneiphof_klein, 10° cap on the peak: p ≈ 0.03; 1e8 facets: CV 6e-4.
  const CellResult big = measure_cell({"kneiphof_klein", 1e8, 0.3, 10, 0, 0, 0}, 4000, 11, d);
  EXPECT_EQ(big.chosen, int(BinomialLevel::kSmooth));
  EXPECT_NEAR(big.levels[3].cv, big.cv_predicted, 0.1 * big.cv_predicted);
  // One facet: the pixel is dark with probability 1 − p.
  const CellResult one = measure_cell({"kneiphof_klein", 1, 0.3, 10, 0, 0, 0}, 4000, 12, d);
  EXPECT_NE(one.chosen, int(BinomialLevel::kSmooth));
  EXPECT_NEAR(one.levels[3].p_zero, one.p_zero_predicted, 0.02);
  EXPECT_GT(one.levels[3].p_zero, 0.9);
  // The smooth level has CV 0 and the model's smooth value.
  EXPECT_EQ(one.levels[0].cv, 0);
  EXPECT_DOUBLE_EQ(one.levels[0].mean, one.smooth);
}

TEST(AdequacyCell, DeliotBelcourOnItsPeakNeverVaries) {
  // p = R D(h)/D(n) = 1 on the peak: every facet reflects, b/(N p) = 1 at every position.
  const CellResult r =
      measure_cell({"deliot_belcour", 10, 0.1, 0, 30, 0, 0}, 1000, 5, decision_for(1, 0.02));
  EXPECT_EQ(r.p, 1);
  EXPECT_EQ(r.levels[3].cv, 0);
  EXPECT_EQ(r.chosen, int(BinomialLevel::kSmooth));
}

std::vector<Cell> small_grid() {
  GridAxes a;
  a.facets = {1, 10, 1e3, 1e5, 1e7};
  a.alpha = {0.1};
  a.light_half_angle_deg = {0, 5};
  a.theta_i_deg = {40};
  return make_grid({"deliot_belcour", "kneiphof_klein"}, a);
}

TEST(AdequacyGrid, SameResultsForAnyThreadCount) {
  const auto cells = small_grid();
  const Decision d = decision_for(cells.size(), 0.02);
  std::vector<CellResult> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = measure_grid(cells, 2000, d);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = measure_grid(cells, 2000, d);
  }
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].chosen, two[i].chosen);
    for (std::size_t l = 0; l < 4; ++l) {
      EXPECT_EQ(one[i].levels[l].mean, two[i].levels[l].mean);
      EXPECT_EQ(one[i].levels[l].cv_diff_ucb, two[i].levels[l].cv_diff_ucb);
    }
  }
}

TEST(AdequacyGrid, ChooserIsNeverRefutedByTheMeasuredTable) {
  const auto cells = small_grid();
  const auto rows = measure_grid(cells, 8000, decision_for(cells.size(), 0.02));
  for (const CellResult& r : rows) {
    EXPECT_FALSE(r.chooser_refuted)
        << r.cell.model << " N_P " << r.cell.facets << " θh " << r.cell.theta_h_deg << " chooser "
        << r.chooser << " measured " << r.chosen;
    // The chooser's level is no cheaper than a level the table shows to be over TAU.
    const LevelStats& s = r.levels[std::size_t(r.chooser)];
    EXPECT_LE(s.mean_diff_lcb, 0.02);
    EXPECT_LE(s.cv_diff_lcb, 0.02);
  }
}

TEST(AdequacyGrid, TenfoldThresholdInTheChooserIsRefuted) {
  // The test above can fail: a chooser told TAU × 10 picks levels the table shows to be over TAU.
  const auto cells = small_grid();
  const auto rows = measure_grid(cells, 8000, decision_for(cells.size(), 0.02));
  int refuted = 0;
  for (const CellResult& r : rows) {
    const int wrong = int(choose_binomial_level(r.cell.facets, r.p, 0.2));
    const LevelStats& s = r.levels[std::size_t(wrong)];
    refuted += (s.mean_diff_lcb > 0.02 || s.cv_diff_lcb > 0.02) ? 1 : 0;
  }
  EXPECT_GT(refuted, 0);
}

}  // namespace
}  // namespace glintlab::verify::adequacy
