// The adequacy decision's calibration (verify/adequacy/decision_calibration.h): the synthetic
// cells differ by exactly what they state, a rule whose bounds are at ten times their level is
// caught above its nominal false-adequate rate (per decision and family-wise) while the real rule
// is not, and the result does not depend on the thread count.
#include "verify/adequacy/decision_calibration.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

namespace glintlab::verify::adequacy {
namespace {

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

double cv_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size())) / m;
}

TEST(AdequacyDecisionCalibration, SyntheticCellsDifferByTheStatedAmount) {
  const int n = 400000;
  std::vector<double> level, exact;
  truth_pair({TruthKind::kMean, 0.3, 1000}, 0.02, 0.25, n, 7, level, exact);
  EXPECT_NEAR(mean_of(exact), 1, 0.003);
  EXPECT_NEAR(cv_of(exact), 0.3, 0.003);
  EXPECT_NEAR(mean_of(level) / mean_of(exact) - 1, 0.025, 0.002);
  EXPECT_NEAR(cv_of(level), 0.3, 0.003);
  truth_pair({TruthKind::kCv, 0.3, 1000}, 0.02, 0, n, 8, level, exact);
  EXPECT_NEAR(mean_of(level), 1, 0.003);
  EXPECT_NEAR(cv_of(level) - cv_of(exact), 0.02, 0.002);
  truth_pair({TruthKind::kSmooth, 0, 1000}, 0.02, 0.05, n, 9, level, exact);
  EXPECT_EQ(level, std::vector<double>(std::size_t(n), 1.0));
  EXPECT_NEAR(cv_of(exact), 0.021, 0.0003);
}

// The mean case at CV 0.1, whose CV bound is never binding: the rate is the mean bound's level.
DecisionCalibrationOptions boundary_options(std::size_t runs) {
  DecisionCalibrationOptions o;
  o.cases = {{TruthKind::kMean, 0.1, 1000}};
  o.deltas = {0};
  o.levels = {0.01};
  o.samples = 500;  // few positions: quick, and the counts (about 90 of 1000 facets) near normal
  o.runs = runs;
  o.table_decisions = 3;  // a table of one cell: the per-decision share is 3.3e-4
  return o;
}

TEST(AdequacyDecisionCalibration, TenfoldLevelIsCaughtTheRealRuleIsNot) {
  DecisionCalibrationOptions o = boundary_options(1500);
  const DecisionCalibration real = calibrate_decision(o);
  ASSERT_EQ(real.rows.size(), 2u);  // nominal 0.01 and the table's share
  EXPECT_NE(real.rows[0].verdict, RateVerdict::kAbove) << real.rows[0].rate;
  EXPECT_NE(real.rows[1].verdict, RateVerdict::kAbove) << real.rows[1].rate;
  o.broken_level_factor = 10;
  const DecisionCalibration broken = calibrate_decision(o);
  EXPECT_EQ(broken.rows[0].verdict, RateVerdict::kAbove) << broken.rows[0].rate;
  EXPECT_GT(broken.rows[0].rate_low, 0.01);
  // Above the boundary (δ = 0.25) the broken rule declares far fewer levels adequate.
  o.deltas = {0.25};
  EXPECT_LT(calibrate_decision(o).rows[0].false_adequate, broken.rows[0].false_adequate / 4);
}

TEST(AdequacyDecisionCalibration, FamilyWiseRateOfTenfoldLevelIsCaught) {
  DecisionCalibrationOptions o = boundary_options(4000);
  const FamilyWiseRow real = calibrate_decision(o).family_wise;
  EXPECT_EQ(real.tables, 4000u / 3);
  EXPECT_EQ(real.pooled_decisions, 4000u);
  EXPECT_NE(real.verdict, RateVerdict::kAbove) << real.implied;
  o.broken_level_factor = 10;
  const FamilyWiseRow broken = calibrate_decision(o).family_wise;
  EXPECT_EQ(broken.verdict, RateVerdict::kAbove) << broken.implied;
  EXPECT_GT(broken.tables_with_false_adequate, real.tables_with_false_adequate);
}

TEST(AdequacyDecisionCalibration, SameResultForAnyThreadCount) {
  DecisionCalibrationOptions o = boundary_options(200);
  o.cases = default_truth_cases();
  o.deltas = {0, 0.05};
  std::vector<std::size_t> counts[2];
  for (int t = 0; t < 2; ++t) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(t + 1));
    for (const DecisionRateRow& r : calibrate_decision(o).rows) counts[t].push_back(r.false_adequate);
  }
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_EQ(counts[0].size(), 7u * 2u * 2u);
}

TEST(AdequacyDecisionCalibration, PooledRowsSumThePooledCases) {
  DecisionCalibrationOptions o = boundary_options(50);
  o.cases = default_truth_cases();
  o.levels = {0.05};
  const DecisionCalibration r = calibrate_decision(o);
  ASSERT_EQ(r.pooled.size(), 2u);  // (δ 0) × (0.05, the table's share)
  std::size_t sum = 0;
  for (const DecisionRateRow& row : r.rows)
    if (!row.table_level && row.truth.cv_exact < 1) sum += row.false_adequate;
  EXPECT_EQ(r.pooled[0].false_adequate, sum);
  EXPECT_EQ(r.pooled[0].decisions, 5u * 50u);  // the CV-1 mean and cv cases left out
  EXPECT_EQ(r.pooled[0].nominal, 0.05);
}

}  // namespace
}  // namespace glintlab::verify::adequacy
