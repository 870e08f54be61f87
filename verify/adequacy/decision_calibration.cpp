#include "verify/adequacy/decision_calibration.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "core/math/rng.h"
#include "verify/calibration.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::adequacy {
namespace {

// The p at which Binomial(trials, p) has coefficient of variation cv: CV² = (1 − p)/(trials·p).
double p_for_cv(std::uint64_t trials, double cv) { return 1 / (1 + double(trials) * cv * cv); }

// Binomial(trials, p) drawn by inversion of its tabulated CDF, the search started from a guide
// table (Chen & Asau 1974): the same distribution as binomial_exact, several times faster for the
// millions of counts a calibration draws. (The calibration tests the decision, not the model's
// sampler.)
class BinomialInverse {
 public:
  BinomialInverse(std::uint64_t trials, double p) : cdf_(trials + 1), guide_(trials + 1) {
    // The probabilities relative to the mode's, by the ratio P(k + 1)/P(k) = (n − k)/(k + 1)·p/q
    // outwards from it (no underflow of P(0) = qⁿ at large n p), then summed and normalised.
    const double n = double(trials), odds = p / (1 - p);
    const std::size_t mode = std::min(std::size_t(std::floor((n + 1) * p)), std::size_t(trials));
    cdf_[mode] = 1;
    for (std::size_t k = mode + 1; k <= trials; ++k)
      cdf_[k] = cdf_[k - 1] * (n - double(k - 1)) / double(k) * odds;
    for (std::size_t k = mode; k-- > 0;)
      cdf_[k] = cdf_[k + 1] * double(k + 1) / (n - double(k)) / odds;
    double sum = 0;
    for (double& c : cdf_) c = sum += c;
    for (double& c : cdf_) c /= sum;
    cdf_.back() = 2;  // above every u: the search always ends
    std::size_t k = 0;
    for (std::size_t j = 0; j < guide_.size(); ++j) {
      while (cdf_[k] <= double(j) / double(guide_.size())) ++k;
      guide_[j] = k;
    }
  }
  // The smallest k with CDF(k) > u, u in [0, 1).
  std::uint64_t operator()(double u) const {
    std::size_t k = guide_[std::min(std::size_t(u * double(guide_.size())), guide_.size() - 1)];
    while (cdf_[k] <= u) ++k;
    return k;
  }

 private:
  std::vector<double> cdf_;
  std::vector<std::size_t> guide_;
};

void normalized_counts(std::uint64_t trials, double p, double scale, std::uint64_t seed,
                       std::uint64_t first_index, int n, std::vector<double>& out) {
  out.resize(std::size_t(n));
  const BinomialInverse draw(trials, p);
  const double per_mean = scale / (double(trials) * p);
  for (int i = 0; i < n; ++i)
    out[std::size_t(i)] =
        double(draw(counter_uniform<double>(seed, first_index + std::uint64_t(i), 0))) * per_mean;
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

std::size_t calibration_cells(const DecisionCalibrationOptions& o) {
  return o.cases.size() * o.deltas.size() * o.runs +
         o.table_deltas.size() * o.tables * o.table_decisions;
}

namespace {

void set_rate(DecisionRateRow& row, double confidence) {
  row.rate = double(row.declared_adequate) / double(row.decisions);
  clopper_pearson(row.declared_adequate, row.decisions, confidence, row.rate_low, row.rate_high);
  row.verdict = row.truly_adequate ? RateVerdict::kPower
                                   : rate_verdict(row.nominal, row.rate_low, row.rate_high);
}

}  // namespace

DecisionCalibration calibrate_decision(const DecisionCalibrationOptions& o) {
  std::vector<std::size_t> table_cases;  // the pooled cases, the tables' decisions in turn
  for (std::size_t c = 0; c < o.cases.size(); ++c)
    if (o.cases[c].pooled) table_cases.push_back(c);
  const bool tables_valid =
      o.tables == 0 || o.table_deltas.empty() ||
      (!table_cases.empty() &&
       std::all_of(o.table_deltas.begin(), o.table_deltas.end(), [](double d) { return d >= 0; }));
  if (o.runs < 1 || o.samples < 2 || o.cases.empty() || o.deltas.empty() ||
      o.table_decisions < 1 || !(o.broken_level_factor >= 1) || !tables_valid)
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

  std::mutex progress;
  const auto step = [&] {
    if (!o.progress) return;
    const std::lock_guard<std::mutex> lock(progress);
    o.progress();
  };
  const std::size_t n_cases = o.cases.size(), n_deltas = o.deltas.size();
  const std::size_t cells = n_cases * n_deltas * o.runs;
  // adequate[(((delta · runs) + run) · cases + case) · levels + level].
  std::vector<unsigned char> adequate(cells * n_levels, 0);
  tbb::parallel_for(std::size_t(0), cells, [&](std::size_t cell) {
    const std::size_t c = cell % n_cases, d = cell / (n_cases * o.runs);
    const std::uint64_t seed = check_seed("adequacy.decision-calibration", cell);
    std::vector<double> level, exact;
    truth_pair(o.cases[c], o.threshold, o.deltas[d], o.samples, seed, level, exact);
    for (std::size_t l = 0; l < n_levels; ++l)
      adequate[cell * n_levels + l] = compare_to_exact(level, exact, decisions[l]).adequate;
    step();
  });

  for (std::size_t c = 0; c < n_cases; ++c)
    for (std::size_t d = 0; d < n_deltas; ++d)
      for (std::size_t l = 0; l < n_levels; ++l) {
        DecisionRateRow row;
        row.truth = o.cases[c];
        if (row.truth.kind == TruthKind::kSmooth) row.truth.cv_exact = o.threshold * (1 + o.deltas[d]);
        row.delta = o.deltas[d];
        row.truly_adequate = row.delta < 0;
        row.nominal = nominal[l];
        row.z = decisions[l].z;
        row.table_level = l == table_index;
        row.decisions = o.runs;
        for (std::size_t run = 0; run < o.runs; ++run)
          row.declared_adequate += adequate[(((d * o.runs) + run) * n_cases + c) * n_levels + l];
        set_rate(row, o.confidence);
        r.rows.push_back(row);
      }

  for (std::size_t d = 0; d < n_deltas; ++d)
    for (std::size_t l = 0; l < n_levels; ++l) {
      DecisionRateRow sum = r.rows[d * n_levels + l];  // δ, level and z of this (δ, level)
      sum.decisions = sum.declared_adequate = 0;
      for (std::size_t c : table_cases) {
        const DecisionRateRow& row = r.rows[(c * n_deltas + d) * n_levels + l];
        sum.decisions += row.decisions;
        sum.declared_adequate += row.declared_adequate;
      }
      if (sum.decisions == 0) continue;
      set_rate(sum, o.confidence);
      r.pooled.push_back(sum);
    }

  // Whole tables: decision j of a table is of the pooled case j mod (their number), at the
  // table's z; fw_adequate[(delta · tables + table) · table_decisions + j].
  const std::size_t per_delta = o.tables * o.table_decisions;
  std::vector<unsigned char> fw_adequate(o.table_deltas.size() * per_delta, 0);
  tbb::parallel_for(std::size_t(0), fw_adequate.size(), [&](std::size_t i) {
    const TruthCase& c = o.cases[table_cases[(i % o.table_decisions) % table_cases.size()]];
    const std::uint64_t seed = check_seed("adequacy.decision-calibration.tables", i);
    std::vector<double> level, exact;
    truth_pair(c, o.threshold, o.table_deltas[i / per_delta], o.samples, seed, level, exact);
    fw_adequate[i] = compare_to_exact(level, exact, r.table_decision).adequate;
    step();
  });
  for (std::size_t d = 0; d < o.table_deltas.size() && o.tables > 0; ++d) {
    FamilyWiseRow fw;
    fw.delta = o.table_deltas[d];
    fw.table_decisions = o.table_decisions;
    fw.tables = o.tables;
    for (std::size_t t = 0; t < o.tables; ++t) {
      std::size_t in_table = 0;
      for (std::size_t j = 0; j < o.table_decisions; ++j)
        in_table += fw_adequate[d * per_delta + t * o.table_decisions + j];
      fw.false_adequate += in_table;
      fw.tables_with_false_adequate += in_table > 0 ? 1 : 0;
    }
    fw.rate = double(fw.tables_with_false_adequate) / double(fw.tables);
    clopper_pearson(fw.tables_with_false_adequate, fw.tables, o.confidence, fw.rate_low,
                    fw.rate_high);
    fw.verdict = rate_verdict(fw.nominal, fw.rate_low, fw.rate_high);
    r.family_wise.push_back(fw);
  }
  return r;
}

}  // namespace glintlab::verify::adequacy
