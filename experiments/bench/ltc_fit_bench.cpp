// Google Benchmark of `glintlab ltc-fit`'s unit of work (core/ltc/ltc_fit.h): one table entry's
// Nelder–Mead fit, as fit_ltc_tables does it (its norm, then the fit from the committed
// parameters of its neighbour at the previous θ_o), for each target at a few entries of the
// 64 × 64 table; and the directional albedo cubature every entry pays once. Run by hand
// (docs/ltc.md "How long the fit takes"):
//   build/release/experiments/bench/glintlab_bench_ltc_fit --benchmark_format=json
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/ltc/ltc_fit.h"
#include "core/ltc/ltc_table.h"

namespace glintlab {
namespace {

// Entry (i, j) of the committed table, i the √α row, j ≥ 1 the θ_o column.
void fit_entry(benchmark::State& state, LtcTarget target) {
  const LtcTables& t = ltc_ggx_tables();
  const int n = t.size, i = int(state.range(0)), j = int(state.range(1));
  const std::size_t k = std::size_t(i) * n + j;
  const LtcFitParameters& warm =
      (target == LtcTarget::kBrdf ? t.brdf_params : t.ndf_params)[k - 1];
  int evaluations = 0;
  for (auto _ : state) {
    const LtcFitResult r = fit_ltc_entry(target, ltc_node_alpha(i, n), ltc_node_theta(j, n), warm);
    benchmark::DoNotOptimize(r.coefficients);
    evaluations = r.evaluations;
  }
  state.counters["objective_evaluations"] = evaluations;
}

void BM_LtcFitEntryBrdf(benchmark::State& state) { fit_entry(state, LtcTarget::kBrdf); }
void BM_LtcFitEntryNdf(benchmark::State& state) { fit_entry(state, LtcTarget::kNdf); }

// Rough, middle and smooth rows at a middle and a grazing θ_o.
void entries(benchmark::internal::Benchmark* b) {
  b->ArgNames({"i", "j"})->Unit(benchmark::kMillisecond);
  for (const int i : {8, 32, 60})
    for (const int j : {32, 60}) b->Args({i, j});
}
BENCHMARK(BM_LtcFitEntryBrdf)->Apply(entries);
BENCHMARK(BM_LtcFitEntryNdf)->Apply(entries);

void BM_LtcAlbedo(benchmark::State& state) {
  const int n = kLtcTableSize;
  for (auto _ : state)
    benchmark::DoNotOptimize(ggx_ltc_albedo(ltc_node_alpha(32, n), std::cos(ltc_node_theta(32, n))));
}
BENCHMARK(BM_LtcAlbedo)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace glintlab

BENCHMARK_MAIN();
