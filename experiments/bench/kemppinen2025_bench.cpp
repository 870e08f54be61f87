// Google Benchmark of Kemppinen et al. 2025 Algorithm 1 (core/glints/kemppinen.h), CPU scalar, one
// core: time per evaluation of D★^f against k, footprint size (the constant-time claim) and the
// erf of Eq. 10, and of the brute-force Eq. 5 (core/glints/kemppinen_reference.h) for contrast;
// the Table 3 analogue (time per pixel, 90° and 25° planes, 3 lights, GGX and Beckmann); and the
// method benchmarks `method/kemppinen_*.dstar_f_vs_{bruteforce,smooth}/k=K,erf=E[,blend=linear]`
// (time per evaluation with the error of Eq. 11 against its references as counters;
// experiments/bench/kemppinen2025_speed_accuracy.h). Read by the figures kemppinen2025-table3 and
// kemppinen2025-speed-accuracy from kemppinen.json of their --bench-from folder, e.g. out/bench:
//   build/release/experiments/bench/glintlab_bench_kemppinen
//   --benchmark_out=out/bench/kemppinen.json
//     --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_reference.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/ndf_kind.h"
#include "experiments/bench/kemppinen2025_speed_accuracy.h"
#include "experiments/bench/kemppinen2025_table3_scene.h"

namespace {

using namespace glintlab;
namespace sa = glintlab::kemppinen_sa;
namespace kt3 = glintlab::kemppinen_table3;

// Args: side (√k), footprint in level-0 cells, erf (0 exact, 1 rational).
void BM_KemppinenEval(benchmark::State& state) {
  kemppinen2025::Params<double> p =
      sa::params({int(state.range(0)), static_cast<kemppinen2025::Erf>(state.range(2)),
                  kemppinen2025::Blend::kRoulette},
                 1);
  const GGX<double> ggx{0.3, 0.3};
  std::uint64_t i = 0;
  for (auto _ : state) {
    const sa::Query q = sa::cost_query(i, double(state.range(1)));
    benchmark::DoNotOptimize(kemppinen2025::eval(p, ggx, q.fp, q.h).d.x);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["points_visited"] = 2.0 * std::pow(double(state.range(0)), 4);
}
BENCHMARK(BM_KemppinenEval)
    ->ArgsProduct({{1, 2, 3, 4},
                   std::vector<std::int64_t>(std::begin(sa::kCostCells), std::end(sa::kCostCells)),
                   {0, 1}})
    ->ArgNames({"side", "footprint_cells", "erf"});

// The brute-force Eq. 5 over the same footprints: cost grows with the footprint's area.
// points_visited: the mean number of (spatial, angular) cell pairs it visits, over 64 queries.
void BM_KemppinenBruteForce(benchmark::State& state) {
  const kemppinen2025::Params<double> p =
      sa::params({1, kemppinen2025::Erf::kExact, kemppinen2025::Blend::kRoulette}, 1);
  const GGX<double> ggx{0.3, 0.3};
  const double cells = double(state.range(0));
  std::int64_t visited = 0;
  for (std::uint64_t k = 0; k < 64; ++k) {
    const sa::Query q = sa::cost_query(k, cells);
    kemppinen2025::reference_filtered(p, ggx, q.fp, q.h, false, &visited);
  }
  std::uint64_t i = 0;
  for (auto _ : state) {
    const sa::Query q = sa::cost_query(i, cells);
    benchmark::DoNotOptimize(kemppinen2025::reference_filtered(p, ggx, q.fp, q.h).x);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["points_visited"] = double(visited) / 64.0;
}
BENCHMARK(BM_KemppinenBruteForce)
    ->RangeMultiplier(2)
    ->Range(1, sa::kBruteForceMaxCells)
    ->ArgName("footprint_cells");

// ---- Table 3 analogue (experiments/bench/kemppinen2025_table3_scene.h) -------------------------
// ns per pixel on one CPU core, scalar double, 3 lights; iteration n shades pixel_of(n).
void BM_Table3(benchmark::State& state, kt3::Cell cell) {
  kt3::with_cell(cell, [&](const auto& shade) {
    std::uint64_t n = 0;
    for (auto _ : state) benchmark::DoNotOptimize(shade(kt3::pixel_of(n++)));
  });
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("ns/pixel, 1 core scalar double, 3 lights");
}

void register_table3() {
  for (const kt3::Cell& c : kt3::cells())
    benchmark::RegisterBenchmark(kt3::cell_name(c).c_str(), BM_Table3, c);
}

// ---- Method benchmarks (speed vs accuracy) -------------------------------------------------

// The reference values and their scale of one (NDF, reference, blending), computed once.
struct RefSet {
  std::vector<sa::Query> q;
  std::vector<double> ref, scale;
};
const RefSet& ref_set(bool ggx, sa::Reference r, kemppinen2025::Blend blend) {
  static std::map<int, RefSet> cache;
  const int key = int(ggx) * 4 + int(r) * 2 + int(blend);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  RefSet s;
  s.q = sa::queries(ggx, r,
                    r == sa::Reference::kBruteForce ? sa::kBruteForceQueries : sa::kSmoothQueries);
  s.ref = sa::reference_all(ggx, r, blend, s.q, &s.scale);
  return cache.emplace(key, std::move(s)).first->second;
}

void set_errors(benchmark::State& state, const sa::Errors& e) {
  state.counters["err_max"] = e.max;
  state.counters["err_rms"] = e.rms;
  state.counters["err_p99"] = e.p99;
  state.counters["err_n"] = e.n;
}

// Algorithm 1 at one setting over the method's queries, cycled; errors outside the timed loop.
void BM_Method(benchmark::State& state, bool ggx, sa::Reference r, sa::Setting s) {
  const RefSet& rs = ref_set(ggx, r, s.blend);
  set_errors(state, sa::errors(sa::eval_all(ggx, s, rs.q), rs.ref, rs.scale));
  const kemppinen2025::Params<double> p = sa::params(s, 1);
  with_ndf(ndf_kind(ggx), sa::kAlpha, sa::kAlpha, [&](const auto& ndf) {
    std::size_t i = 0;
    for (auto _ : state) {
      const sa::Query& q = rs.q[i];
      benchmark::DoNotOptimize(kemppinen2025::eval(p, ndf, q.fp, q.h).d.x);
      i = i + 1 == rs.q.size() ? 0 : i + 1;
    }
    return 0;
  });
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(sa::reference_label(r));
}

// The brute-force reference itself (errors 0 by definition) over the same queries.
void BM_MethodReference(benchmark::State& state, bool ggx) {
  const RefSet& rs = ref_set(ggx, sa::Reference::kBruteForce, kemppinen2025::Blend::kRoulette);
  set_errors(state, {0, 0, 0, int(rs.q.size())});
  const kemppinen2025::Params<double> p =
      sa::params({1, kemppinen2025::Erf::kExact, kemppinen2025::Blend::kRoulette}, 1);
  with_ndf(ndf_kind(ggx), sa::kAlpha, sa::kAlpha, [&](const auto& ndf) {
    std::size_t i = 0;
    for (auto _ : state) {
      const sa::Query& q = rs.q[i];
      benchmark::DoNotOptimize(kemppinen2025::reference_filtered(p, ndf, q.fp, q.h).x);
      i = i + 1 == rs.q.size() ? 0 : i + 1;
    }
    return 0;
  });
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("the reference: Eq. 5 brute force over all points; err = 0");
}

void register_methods() {
  for (bool ggx : {true, false}) {
    for (sa::Reference r : {sa::Reference::kBruteForce, sa::Reference::kSmooth})
      for (const sa::Setting& s : sa::settings(r)) {
        const std::string name = "method/" + sa::method_id(ggx, r) + "/" + sa::setting_name(s);
        benchmark::RegisterBenchmark(name.c_str(), BM_Method, ggx, r, s);
      }
    const std::string name =
        "method/" + sa::method_id(ggx, sa::Reference::kBruteForce) + "/method=bruteforce";
    benchmark::RegisterBenchmark(name.c_str(), BM_MethodReference, ggx);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_table3();
  register_methods();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
