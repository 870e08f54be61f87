#include "experiments/compare/eval_timing.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/model_layout.h"
#include "core/simd/model_batch.h"
#include "verify/conformance/common.h"

namespace glintlab::experiments::compare {
namespace {

// Query columns (layout order, with corners) of `rows` queries: the first scene's query with ωo
// on a golden-angle spiral over the upper hemisphere, so the timing mixes lobe and tail.
std::vector<std::vector<double>> timing_queries(const ModelEntry& m, const CompareBudget& b) {
  const ModelQuery<double> base =
      verify::conformance::make_query(m, b.thetas_deg.front(), kSceneFootprint);
  std::vector<std::vector<double>> cols(kQueryLayout.size(), std::vector<double>(b.timing_rows));
  for (std::size_t i = 0; i < b.timing_rows; ++i) {
    ModelQuery<double> q = base;
    const double z = (double(i) + 0.5) / double(b.timing_rows);
    const double r = std::sqrt(1 - z * z), phi = double(i) * std::numbers::pi * (3 - std::sqrt(5.0));
    q.wo = {r * std::cos(phi), r * std::sin(phi), z};
    const QueryRow<double> row = to_row(q);
    for (std::size_t k = 0; k < row.size(); ++k) cols[k][i] = row[k];
  }
  return cols;
}

double ns_per_eval(const ModelEntry& m, const std::vector<double>& params,
                   const std::vector<std::vector<double>>& cols, simd::Isa isa,
                   const CompareBudget& b) {
  std::vector<simd::Column<double>> query;
  for (const auto& c : cols) query.push_back({c.data(), 1});
  std::vector<std::vector<double>> out(2 + m.intermediates.size(),
                                       std::vector<double>(b.timing_rows));
  std::vector<double*> outputs;
  for (auto& o : out) outputs.push_back(o.data());
  using clock = std::chrono::steady_clock;
  double best = INFINITY;
  for (int round = 0; round < 3; ++round) {
    long calls = 0;
    const auto start = clock::now();
    double seconds = 0;
    do {
      simd::eval_batch(m, params, query, outputs, b.timing_rows, isa);
      ++calls;
      seconds = std::chrono::duration<double>(clock::now() - start).count();
    } while (seconds < b.timing_seconds);
    best = std::min(best, seconds * 1e9 / (double(calls) * double(b.timing_rows)));
  }
  return best;
}

}  // namespace

EvalTiming time_evaluations(const ModelEntry& m, const CompareBudget& b) {
  const std::vector<double> params = resolve_params(m, {});
  const auto cols = timing_queries(m, b);
  EvalTiming t;
  t.batched = simd::is_batched(m);
  const simd::Isa best = simd::default_isa();
  t.best_isa = std::string(simd::isa_name(best));
  t.scalar_ns = ns_per_eval(m, params, cols, simd::Isa::kScalar, b);
  t.best_ns = best == simd::Isa::kScalar ? t.scalar_ns : ns_per_eval(m, params, cols, best, b);
  return t;
}

}  // namespace glintlab::experiments::compare
