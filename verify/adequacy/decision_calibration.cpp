#include "verify/adequacy/decision_calibration.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>
#include <stdexcept>

#include "core/glints/binomial.h"
#include "verify/calibration.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::adequacy {
namespace {

// The p at which Binomial(trials, p) has coefficient of variation cv: CV² = (1 − p)/(trials·p).
double p_for_cv(std::uint64_t trials, double cv) { return 1 / (1 + double(trials) * cv * cv); }

void normalized_counts(std::uint64_t trials, double p, double scale, std::uint64_t seed,
                       std::uint64_t first_index, int n, std::vector<double>& out) {
  out.resize(std::size_t(n));
  const double per_mean = scale / (double(trials) * p);
  for (int i = 0; i < n; ++i)
    out[std::size_t(i)] =
        double(binomial_exact(trials, p, seed, first_index + std::uint64_t(i))) * per_mean;
}

}  // namespace

std::vector<TruthCase> default_truth_cases() {
  std::vector<TruthCase> cases;
  for (TruthKind k : {TruthKind::kMean, TruthKind::kCv})
    for (double cv : {1.0, 0.3, 0.1}) cases.push_back({k, cv, 1000, cv < 1});
  cases.push_back({TruthKind::kSmooth, 0, 1000, true});
  return cases;
}

void truth_pair(const TruthCase& c, double threshold, double delta, int n, std::uint64_t seed,
                std::vector<double>& level, std::vector<double>& exact) {
  const double diff = threshold * (1 + delta);
  // The exact level at positions 0..n−1 of the counter stream, the cheaper one at n..2n−1:
  // independent draws, paired by position as the table pairs them.
  const auto level_first = std::uint64_t(n);
  switch (c.kind) {
    case TruthKind::kMean: {
      const double p = p_for_cv(c.trials, c.cv_exact);
      normalized_counts(c.trials, p, 1, seed, 0, n, exact);
      normalized_counts(c.trials, p, 1 + diff, seed, level_first, n, level);
      return;
    }
    case TruthKind::kCv:
      normalized_counts(c.trials, p_for_cv(c.trials, c.cv_exact), 1, seed, 0, n, exact);
      normalized_counts(c.trials, p_for_cv(c.trials, c.cv_exact + diff), 1, seed, level_first, n,
                        level);
      return;
    case TruthKind::kSmooth:
      normalized_counts(c.trials, p_for_cv(c.trials, diff), 1, seed, 0, n, exact);
      level.assign(std::size_t(n), 1.0);
      return;
  }
}

RateVerdict rate_verdict(double nominal, double low, double high) {
  return nominal < low ? RateVerdict::kAbove : nominal > high ? RateVerdict::kBelow
                                                              : RateVerdict::kWithin;
}

DecisionCalibration calibrate_decision(const DecisionCalibrationOptions& o) {
  if (o.runs < 1 || o.samples < 2 || o.cases.empty() || o.deltas.empty() ||
      o.table_decisions < 1 || !(o.broken_level_factor >= 1))
    throw std::invalid_argument("calibrate_decision: empty calibration");
  DecisionCalibration r;
  r.options = o;
  r.options.progress = {};
  // The table's own z: its Šidák share of kFamilyWiseRate over table_decisions decisions (as
  // decision_for gives it for table_decisions / 3 cells).
  const double table_level = sidak_level(kFamilyWiseRate, o.table_decisions);
  r.table_decision = decision_at_level(table_level * o.broken_level_factor, o.threshold);
  std::vector<Decision> decisions;
  std::vector<double> nominal;
  for (double l : o.levels) {
    decisions.push_back(decision_at_level(l * o.broken_level_factor, o.threshold));
    nominal.push_back(l);
  }
  decisions.push_back(r.table_decision);
  nominal.push_back(table_level);
  const std::size_t n_levels = decisions.size(), table_index = n_levels - 1;

  const std::size_t n_cases = o.cases.size(), n_deltas = o.deltas.size();
  const std::size_t cells = n_cases * n_deltas * o.runs;
  // adequate[(((delta · runs) + run) · cases + case) · levels + level]: at δ = 0 the decisions in
  // run-major order are the cases in turn, the order the family-wise tables take them in.
  std::vector<unsigned char> adequate(cells * n_levels, 0);
  std::mutex progress;
  tbb::parallel_for(std::size_t(0), cells, [&](std::size_t cell) {
    const std::size_t c = cell % n_cases, d = cell / (n_cases * o.runs);
    const std::uint64_t seed = check_seed("adequacy.decision-calibration", cell);
    std::vector<double> level, exact;
    truth_pair(o.cases[c], o.threshold, o.deltas[d], o.samples, seed, level, exact);
    for (std::size_t l = 0; l < n_levels; ++l)
      adequate[cell * n_levels + l] = compare_to_exact(level, exact, decisions[l]).adequate;
    if (o.progress) {
      const std::lock_guard<std::mutex> lock(progress);
      o.progress();
    }
  });

  for (std::size_t c = 0; c < n_cases; ++c)
    for (std::size_t d = 0; d < n_deltas; ++d)
      for (std::size_t l = 0; l < n_levels; ++l) {
        DecisionRateRow row;
        row.truth = o.cases[c];
        if (row.truth.kind == TruthKind::kSmooth) row.truth.cv_exact = o.threshold * (1 + o.deltas[d]);
        row.delta = o.deltas[d];
        row.nominal = nominal[l];
        row.z = decisions[l].z;
        row.table_level = l == table_index;
        row.decisions = o.runs;
        for (std::size_t run = 0; run < o.runs; ++run)
          row.false_adequate += adequate[(((d * o.runs) + run) * n_cases + c) * n_levels + l];
        row.rate = double(row.false_adequate) / double(row.decisions);
        clopper_pearson(row.false_adequate, row.decisions, o.confidence, row.rate_low,
                        row.rate_high);
        row.verdict = rate_verdict(row.nominal, row.rate_low, row.rate_high);
        r.rows.push_back(row);
      }

  for (std::size_t d = 0; d < n_deltas; ++d)
    for (std::size_t l = 0; l < n_levels; ++l) {
      DecisionRateRow sum = r.rows[d * n_levels + l];  // δ, level and z of this (δ, level)
      sum.decisions = sum.false_adequate = 0;
      for (std::size_t c = 0; c < n_cases; ++c) {
        if (!o.cases[c].pooled) continue;
        const DecisionRateRow& row = r.rows[(c * n_deltas + d) * n_levels + l];
        sum.decisions += row.decisions;
        sum.false_adequate += row.false_adequate;
      }
      if (sum.decisions == 0) continue;
      sum.rate = double(sum.false_adequate) / double(sum.decisions);
      clopper_pearson(sum.false_adequate, sum.decisions, o.confidence, sum.rate_low, sum.rate_high);
      sum.verdict = rate_verdict(sum.nominal, sum.rate_low, sum.rate_high);
      r.pooled.push_back(sum);
    }

  FamilyWiseRow& fw = r.family_wise;
  fw.table_decisions = o.table_decisions;
  std::size_t boundary = n_deltas;  // the δ = 0 decisions (the first δ equal to 0)
  for (std::size_t d = 0; d < n_deltas && boundary == n_deltas; ++d)
    if (o.deltas[d] == 0) boundary = d;
  if (boundary < n_deltas) {
    const std::size_t per_delta = o.runs * n_cases;
    const auto at = [&](std::size_t j) {
      return adequate[(boundary * per_delta + j) * n_levels + table_index] != 0;
    };
    fw.tables = per_delta / o.table_decisions;
    for (std::size_t t = 0; t < fw.tables; ++t) {
      bool any = false;
      for (std::size_t j = 0; j < o.table_decisions; ++j) any = any || at(t * o.table_decisions + j);
      fw.tables_with_false_adequate += any ? 1 : 0;
    }
    if (fw.tables > 0) {
      fw.rate = double(fw.tables_with_false_adequate) / double(fw.tables);
      clopper_pearson(fw.tables_with_false_adequate, fw.tables, o.confidence, fw.rate_low,
                      fw.rate_high);
    }
    fw.pooled_decisions = per_delta;
    for (std::size_t j = 0; j < per_delta; ++j) fw.pooled_false_adequate += at(j) ? 1 : 0;
    double q_low = 0, q_high = 1;
    clopper_pearson(fw.pooled_false_adequate, fw.pooled_decisions, o.confidence, q_low, q_high);
    const double q = double(fw.pooled_false_adequate) / double(fw.pooled_decisions);
    fw.implied = sidak(q, o.table_decisions);
    fw.implied_low = sidak(q_low, o.table_decisions);
    fw.implied_high = sidak(q_high, o.table_decisions);
    // The verdict from the pooled interval: it rests on table_decisions times more trials.
    fw.verdict = rate_verdict(fw.nominal, fw.implied_low, fw.implied_high);
  }
  return r;
}

}  // namespace glintlab::verify::adequacy
