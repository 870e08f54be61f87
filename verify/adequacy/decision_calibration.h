// Calibration of the adequacy decision (compare_to_exact in binomial_adequacy.h): its false
// "adequate" rate measured on synthetic cells whose truth is known. Each cell pairs an "exact"
// level, Binomial(N, p)/(N p) counts at n positions (mean 1, skewed like the real cells' counts),
// with a cheaper "level" whose difference from it is exactly TAU·(1 + δ):
//   * mean: an independent draw of the same count scaled by 1 + TAU·(1 + δ) (same CV);
//   * cv: an independent Binomial(N, p′)/(N p′) with p′ chosen so that its CV is the exact one's
//     plus TAU·(1 + δ) (same mean);
//   * smooth: the constant 1 against an exact level whose CV is TAU·(1 + δ) (the smooth level at
//     the predicted boundary).
// At δ = 0 the cheaper level is exactly not adequate, so every "adequate" is a false one: a
// calibrated rule declares it with probability at most the bound's one-sided level (equal to it
// where the other difference's bound is never binding). The same function the table uses decides,
// at the real table's z and at larger nominal levels where the rate can be measured precisely.
// Decisions are also grouped into tables of the real table's size (every decision at the boundary,
// the worst case) to measure the family-wise rate directly.
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
  std::vector<double> deltas = {0, 0.05, 0.25};
  // Nominal one-sided levels besides the real table's Šidák share (which is always measured).
  std::vector<double> levels = {0.05, 0.01, 1e-3, 1e-4};
  double confidence = 0.95;          // of the Clopper–Pearson intervals
  // 1 for the rule as the table uses it. Above 1, a deliberately miscalibrated rule: each bound is
  // computed at its nominal level times this factor (z too small) while its rate is still judged
  // against the nominal level; the tests show the calibration catching it.
  double broken_level_factor = 1;
  std::function<void()> progress;    // once per synthetic cell, never concurrently
};

// Where a measured rate lies against the nominal one.
enum class RateVerdict { kWithin, kBelow, kAbove };
inline constexpr std::array<std::string_view, 3> kRateVerdictNames = {"within", "below", "ABOVE"};
RateVerdict rate_verdict(double nominal, double low, double high);

// One (case, δ, nominal level): how often the rule declared the cheaper level adequate.
struct DecisionRateRow {
  TruthCase truth;
  double delta = 0;
  double nominal = 0;  // the bound's one-sided level
  double z = 0;
  bool table_level = false;  // the real table's Šidák share
  std::size_t decisions = 0, false_adequate = 0;
  double rate = 0, rate_low = 0, rate_high = 1;
  RateVerdict verdict = RateVerdict::kWithin;
};

// Tables of table_decisions boundary decisions (δ = 0, the cases in turn) at the real z: how many
// declared any level adequate, against the family-wise rate kFamilyWiseRate.
struct FamilyWiseRow {
  std::size_t table_decisions = 0, tables = 0, tables_with_false_adequate = 0;
  double nominal = kFamilyWiseRate;
  double rate = 0, rate_low = 0, rate_high = 1;
  // The same from every δ = 0 decision at the real z pooled (q their false-adequate rate, with its
  // interval): 1 − (1 − q)^table_decisions, the decisions being independent.
  std::size_t pooled_decisions = 0, pooled_false_adequate = 0;
  double implied = 0, implied_low = 0, implied_high = 1;
  RateVerdict verdict = RateVerdict::kWithin;
};

struct DecisionCalibration {
  DecisionCalibrationOptions options;
  Decision table_decision;  // the real table's TAU and z
  std::vector<DecisionRateRow> rows;
  // Per (δ, nominal level), the rows of the cases marked `pooled` summed (their `truth` is not
  // meaningful): the rate the bound's level promises, measured on more decisions.
  std::vector<DecisionRateRow> pooled;
  FamilyWiseRow family_wise;
};

// Every (case, δ) cell in parallel (TBB); identical results for any thread count.
DecisionCalibration calibrate_decision(const DecisionCalibrationOptions& o);

}  // namespace glintlab::verify::adequacy
