// The adequacy decision's calibration (verify/adequacy/decision_calibration.h): the synthetic
// cells differ by exactly what they state, a rule whose bounds are at ten times their level is
// caught above its nominal false-adequate rate (per decision and family-wise, on whole tables)
// while the real rule is not, truly adequate cells are declared adequate (the power), and the
// result does not depend on the thread count.
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
  // The counts are Binomial(1000, p): at CV 1 (p = 1/1001) P(0) = (1 − p)^1000 = 0.3681.
  truth_pair({TruthKind::kMean, 1, 1000}, 0.02, 0, n, 10, level, exact);
  double zeros = 0;
  for (double x : exact) zeros += x == 0 ? 1 : 0;
  EXPECT_NEAR(zeros / n, std::pow(1 - 1 / 1001.0, 1000), 0.003);
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
  o.tables = 0;
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
  EXPECT_LT(calibrate_decision(o).rows[0].declared_adequate,
            broken.rows[0].declared_adequate / 4);
}

TEST(AdequacyDecisionCalibration, FamilyWiseRateOfTenfoldLevelIsCaught) {
  // 4000 tables of one cell (3 decisions) at the boundary: about 4 with a false adequate at the
  // family-wise rate 1e-3, about 40 for the broken rule.
  DecisionCalibrationOptions o = boundary_options(1);
  o.tables = 4000;
  o.table_deltas = {0};
  const std::vector<FamilyWiseRow> real = calibrate_decision(o).family_wise;
  ASSERT_EQ(real.size(), 1u);
  EXPECT_EQ(real[0].tables, 4000u);
  EXPECT_EQ(real[0].table_decisions, 3u);
  EXPECT_NE(real[0].verdict, RateVerdict::kAbove) << real[0].rate;
  o.broken_level_factor = 10;
  const std::vector<FamilyWiseRow> broken = calibrate_decision(o).family_wise;
  EXPECT_EQ(broken[0].verdict, RateVerdict::kAbove) << broken[0].rate;
  EXPECT_GT(broken[0].tables_with_false_adequate, real[0].tables_with_false_adequate);
  EXPECT_GE(broken[0].false_adequate, broken[0].tables_with_false_adequate);
}

TEST(AdequacyDecisionCalibration, TrulyAdequateCellsAreDeclaredAdequate) {
  // The mean case at CV 0.1 and 8000 positions: a difference of TAU/2 has an upper bound of about
  // TAU (0.5 + 0.2) at level 0.01, so it is declared adequate nearly always; nearer TAU less often.
  DecisionCalibrationOptions o = boundary_options(200);
  o.samples = 8000;
  o.deltas = {-0.5, -0.1, 0};
  const DecisionCalibration r = calibrate_decision(o);
  ASSERT_EQ(r.rows.size(), 3u * 2u);
  EXPECT_TRUE(r.rows[0].truly_adequate);
  EXPECT_EQ(r.rows[0].verdict, RateVerdict::kPower);
  EXPECT_GT(r.rows[0].rate, 0.95);
  EXPECT_LT(r.rows[2].rate, r.rows[0].rate);  // δ = −0.1
  EXPECT_LT(r.rows[4].rate, r.rows[2].rate);  // δ = 0
  EXPECT_FALSE(r.rows[4].truly_adequate);
  EXPECT_NE(r.rows[4].verdict, RateVerdict::kPower);
}

TEST(AdequacyDecisionCalibration, SameResultForAnyThreadCount) {
  DecisionCalibrationOptions o = boundary_options(200);
  o.cases = default_truth_cases();
  o.deltas = {-0.25, 0, 0.05};
  o.tables = 30;
  o.table_deltas = {0};
  std::vector<std::size_t> counts[2];
  for (int t = 0; t < 2; ++t) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(t + 1));
    const DecisionCalibration r = calibrate_decision(o);
    for (const DecisionRateRow& row : r.rows) counts[t].push_back(row.declared_adequate);
    for (const FamilyWiseRow& fw : r.family_wise) counts[t].push_back(fw.false_adequate);
  }
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_EQ(counts[0].size(), 7u * 3u * 2u + 1u);
}

TEST(AdequacyDecisionCalibration, PooledRowsSumThePooledCases) {
  DecisionCalibrationOptions o = boundary_options(50);
  o.cases = default_truth_cases();
  o.levels = {0.05};
  const DecisionCalibration r = calibrate_decision(o);
  ASSERT_EQ(r.pooled.size(), 2u);  // (δ 0) × (0.05, the table's share)
  std::size_t sum = 0;
  for (const DecisionRateRow& row : r.rows)
    if (!row.table_level && row.truth.cv_exact < 1) sum += row.declared_adequate;
  EXPECT_EQ(r.pooled[0].declared_adequate, sum);
  EXPECT_EQ(r.pooled[0].decisions, 5u * 50u);  // the CV-1 mean and cv cases left out
  EXPECT_EQ(r.pooled[0].nominal, 0.05);
}

}  // namespace
}  // namespace glintlab::verify::adequacy
