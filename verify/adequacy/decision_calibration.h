// Calibration of the adequacy decision (compare_to_exact in binomial_adequacy.h): its false
// "adequate" rate measured on synthetic cells whose truth is known. Each cell pairs an "exact"
// level, Binomial(N, p)/(N p) counts at n positions (mean 1, skewed like the real cells' counts),
// with a cheaper "level" whose difference from it is exactly TAU·(1 + δ):
//   * mean: an independent draw of the same count scaled by 1 + TAU·(1 + δ) (same CV);
//   * cv: an independent Binomial(N, p′)/(N p′) with p′ chosen so that its CV is the exact one's
//     plus TAU·(1 + δ) (same mean);
//   * smooth: the constant 1 against an exact level whose CV is TAU·(1 + δ) (the smooth level at
//     the predicted boundary).
// At δ ≥ 0 the cheaper level is not adequate, so every "adequate" is a false one: a calibrated
// rule declares it with probability at most the bound's one-sided level (equal to it at δ = 0
// where the other difference's bound is never binding). At δ < 0 the level is truly adequate and
// the rate of "adequate" is the rule's power. The same function the table uses decides, at the
// real table's z and at larger nominal levels where the rate can be measured precisely. The
// family-wise rate is measured directly on whole tables of the real table's size whose every
// decision is at TAU·(1 + δ) (the worst case for δ = 0), decided at the table's z.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "verify/adequacy/binomial_adequacy.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::adequacy {

enum class TruthKind { kMean, kCv, kSmooth };
inline constexpr std::array<std::string_view, 3> kTruthKindNames = {"mean", "cv", "smooth"};

// One synthetic cell: the exact level's count Binomial(trials, p) with p set so that its CV is
// cv_exact (p = 1/(1 + trials·cv_exact²)); for kSmooth cv_exact is TAU·(1 + δ) instead.
struct TruthCase {
  TruthKind kind = TruthKind::kMean;
  double cv_exact = 1;
  std::uint64_t trials = 1000;
  // Counted in the pooled rates (DecisionCalibration::pooled). Not for a case whose other
  // difference's bound alone is wider than TAU at the quick budget's positions (CV 1: the mean
  // ratio of two such samples has a standard error of about 0.016 at 8000 positions), where the
  // rule never declares adequate and the rate says nothing about the bound's level.
  bool pooled = true;
};

// The cases of a calibration run: mean and CV differences at exact CVs 1, 0.3 and 0.1 (about 1,
// 11 and 90 reflecting facets of 1000: strongly to mildly skewed counts), and the smooth level.
std::vector<TruthCase> default_truth_cases();

// The paired values of one synthetic cell at n positions: `level` differs from `exact` by
// threshold·(1 + delta) in the case's statistic. Deterministic in seed.
void truth_pair(const TruthCase& c, double threshold, double delta, int n, std::uint64_t seed,
                std::vector<double>& level, std::vector<double>& exact);

struct DecisionCalibrationOptions {
  double threshold = kDefaultThreshold;
  int samples = 8000;                // positions per cell (quick 8000, full 32000)
  std::size_t table_decisions = 0;   // (cell, cheaper level) decisions of the real table
  std::size_t runs = 2000;           // synthetic cells per (case, δ)
  std::vector<TruthCase> cases = default_truth_cases();
  // δ < 0: truly adequate (the power); δ = 0: the boundary; δ > 0: just beyond the tolerance.
  std::vector<double> deltas = {-0.5, -0.25, -0.1, 0, 0.05, 0.1, 0.25};
  // Family-wise: `tables` whole tables of table_decisions decisions at each of table_deltas (all
  // ≥ 0), the pooled cases in turn, decided at the table's z only.
  std::size_t tables = 20;
  std::vector<double> table_deltas = {0, 0.05, 0.1, 0.25};
  // Nominal one-sided levels besides the real table's Šidák share (which is always measured).
  std::vector<double> levels = {0.05, 0.01, 1e-3, 1e-4};
  double confidence = 0.95;          // of the Clopper–Pearson intervals
  // 1 for the rule as the table uses it. Above 1, a deliberately miscalibrated rule: each bound is
  // computed at its nominal level times this factor (z too small) while its rate is still judged
  // against the nominal level; the tests show the calibration catching it.
  double broken_level_factor = 1;
  std::function<void()> progress;    // once per synthetic cell, never concurrently
};

// Where a measured false-adequate rate lies against the nominal one; kPower for a row of truly
// adequate cells (δ < 0), whose rate is the power and has no nominal level.
enum class RateVerdict { kWithin, kBelow, kAbove, kPower };
inline constexpr std::array<std::string_view, 4> kRateVerdictNames = {"within", "below", "ABOVE",
                                                                      "power"};
RateVerdict rate_verdict(double nominal, double low, double high);

// One (case, δ, nominal level): how often the rule declared the cheaper level adequate: falsely
// for δ ≥ 0, rightly (the power) for δ < 0.
struct DecisionRateRow {
  TruthCase truth;
  double delta = 0;
  double nominal = 0;  // the bound's one-sided level
  double z = 0;
  bool table_level = false;  // the real table's Šidák share
  bool truly_adequate = false;  // δ < 0
  std::size_t decisions = 0, declared_adequate = 0;
  double rate = 0, rate_low = 0, rate_high = 1;
  RateVerdict verdict = RateVerdict::kWithin;
};

// At one δ ≥ 0: tables of table_decisions decisions (the pooled cases in turn) at the real z, and
// how many declared any level adequate (a false adequate), against the family-wise rate
// kFamilyWiseRate.
struct FamilyWiseRow {
  double delta = 0;
  std::size_t table_decisions = 0, tables = 0, tables_with_false_adequate = 0;
  double nominal = kFamilyWiseRate;
  double rate = 0, rate_low = 0, rate_high = 1;
  std::size_t false_adequate = 0;  // over all the tables' decisions
  RateVerdict verdict = RateVerdict::kWithin;
};

struct DecisionCalibration {
  DecisionCalibrationOptions options;
  Decision table_decision;  // the real table's TAU and z
  std::vector<DecisionRateRow> rows;
  // Per (δ, nominal level), the rows of the cases marked `pooled` summed (their `truth` is not
  // meaningful): the rate the bound's level promises, measured on more decisions.
  std::vector<DecisionRateRow> pooled;
  std::vector<FamilyWiseRow> family_wise;  // one per table_deltas
};

// Synthetic cells a calibration with these options draws (the rows' and the tables').
std::size_t calibration_cells(const DecisionCalibrationOptions& o);

// Every (case, δ) cell and every table in parallel (TBB); identical results for any thread count.
DecisionCalibration calibrate_decision(const DecisionCalibrationOptions& o);

}  // namespace glintlab::verify::adequacy
